#version 460
// The macrocell grid of one volume (shared/volume.h), one invocation per macrocell: the largest extinction
// its transfer-function table gives over the range of voxel values in the cell (its corner planes
// included: trilinear interpolation never leaves that range). A piecewise-linear table peaks at an end of
// that range or at an entry inside it, so the bound is exact; it is raised by 1e-5 so that float rounding
// in the tracking kernels stays under it. Run when a scene is built (core/scene/VolumeMajorants.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/volume.h"

layout(local_size_x = 64) in;

layout(push_constant) uniform Push { MajorantParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer VolumesRef { VolumeRecord volumes[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer VolumeDataRef { float values[]; };

float tableExtinction(VolumeRecord v, VolumeDataRef data, uint entry) {
    return data.values[v.tableOffset + 4u * entry + 3u];
}

// The table's extinction at fractional entry `position`, interpolated as the tracking kernels do.
float extinctionAt(VolumeRecord v, VolumeDataRef data, float position) {
    uint i = min(uint(position), v.tableSize - 2u);
    float w = position - float(i);
    return tableExtinction(v, data, i) * (1.0 - w) + tableExtinction(v, data, i + 1u) * w;
}

void main() {
    VolumeRecord v = VolumesRef(params.volumes).volumes[params.volume];
    uint cell = params.firstCell + gl_GlobalInvocationID.x;
    if (cell >= v.macroX * v.macroY * v.macroZ) return;
    VolumeDataRef data = VolumeDataRef(params.volumeData), voxels = VolumeDataRef(v.voxels);
    uvec3 macro = uvec3(cell % v.macroX, (cell / v.macroX) % v.macroY, cell / (v.macroX * v.macroY));
    uvec3 extent = uvec3(v.dimX - 1u, v.dimY - 1u, v.dimZ - 1u);
    uvec3 first = macro * VOLUME_MACROCELL;
    uvec3 last = min(first + VOLUME_MACROCELL, extent);
    float lowest = 3.402823e38, highest = -3.402823e38;
    for (uint z = first.z; z <= last.z; ++z)
        for (uint y = first.y; y <= last.y; ++y) {
            uint row = (z * v.dimY + y) * v.dimX;
            for (uint x = first.x; x <= last.x; ++x) {
                float value = voxels.values[row + x];
                lowest = min(lowest, value);
                highest = max(highest, value);
            }
        }
    float top = float(v.tableSize - 1u);
    float scale = top * v.valueRange.y;
    float p0 = clamp((lowest - v.valueRange.x) * scale, 0.0, top);
    float p1 = clamp((highest - v.valueRange.x) * scale, 0.0, top);
    float majorant = max(extinctionAt(v, data, p0), extinctionAt(v, data, p1));
    // The entries strictly inside (p0, p1), in nested loops: lavapipe ends any one loop after 65,535
    // iterations, and a table may be longer than that.
    for (uint chunk = uint(ceil(p0)); float(chunk) < p1; chunk += 32768u)
        for (uint e = chunk; e < chunk + 32768u && float(e) < p1; ++e) majorant = max(majorant, tableExtinction(v, data, e));
    data.values[v.majorantOffset + cell] = majorant * (1.0 + 1e-5);
}
