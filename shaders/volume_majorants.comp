#version 460
// The macrocell grids of one volume (shared/volume.h), one invocation per coarse macrocell: for it and for
// each fine macrocell under it, the largest extinction its transfer-function table gives over the range
// of voxel values in the cell (its corner planes included: trilinear interpolation never leaves that
// range). A piecewise-linear table peaks at an end of that range or at an entry inside it, so the bound
// is exact; it is raised by 1e-5 so that float rounding in the tracking kernels stays under it. The fine
// cells tile the coarse one, planes included, so the coarse range is the union of theirs. Also written:
// the sum of the fine majorants under each coarse macrocell, from which the host chooses the grid. Run
// when a scene is built (core/scene/VolumeMajorants.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/volume.h"

layout(local_size_x = 64) in;

layout(push_constant) uniform Push { MajorantParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer VolumesRef { VolumeRecord volumes[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer VolumeDataRef { float values[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer SumsRef { float values[]; };

float tableExtinction(VolumeRecord v, VolumeDataRef data, uint entry) {
    return data.values[v.tableOffset + 4u * entry + 3u];
}

// The table's extinction at fractional entry `position`, interpolated as the tracking kernels do.
float extinctionAt(VolumeRecord v, VolumeDataRef data, float position) {
    uint i = min(uint(position), v.tableSize - 2u);
    float w = position - float(i);
    return tableExtinction(v, data, i) * (1.0 - w) + tableExtinction(v, data, i + 1u) * w;
}

// The largest extinction over voxel values [lowest, highest], raised by 1e-5.
float majorantOver(VolumeRecord v, VolumeDataRef data, float lowest, float highest) {
    float top = float(v.tableSize - 1u);
    float scale = top * v.valueRange.y;
    float p0 = clamp((lowest - v.valueRange.x) * scale, 0.0, top);
    float p1 = clamp((highest - v.valueRange.x) * scale, 0.0, top);
    float majorant = max(extinctionAt(v, data, p0), extinctionAt(v, data, p1));
    // The entries strictly inside (p0, p1), in nested loops: lavapipe ends any one loop after 65,535
    // iterations, and a table may be longer than that.
    for (uint chunk = uint(ceil(p0)); float(chunk) < p1; chunk += 32768u)
        for (uint e = chunk; e < chunk + 32768u && float(e) < p1; ++e) majorant = max(majorant, tableExtinction(v, data, e));
    return majorant * (1.0 + 1e-5);
}

void main() {
    VolumeRecord v = VolumesRef(params.volumes).volumes[params.volume];
    uvec3 extent = uvec3(v.dimX - 1u, v.dimY - 1u, v.dimZ - 1u);
    uvec3 coarseDims = max((extent + VOLUME_MACROCELL_COARSE - 1u) / VOLUME_MACROCELL_COARSE, uvec3(1u));
    uvec3 fineDims = max((extent + VOLUME_MACROCELL_FINE - 1u) / VOLUME_MACROCELL_FINE, uvec3(1u));
    uint cell = params.firstCell + gl_GlobalInvocationID.x;
    if (cell >= coarseDims.x * coarseDims.y * coarseDims.z) return;
    VolumeDataRef data = VolumeDataRef(params.volumeData), voxels = VolumeDataRef(v.voxels);
    uvec3 macro = uvec3(cell % coarseDims.x, (cell / coarseDims.x) % coarseDims.y, cell / (coarseDims.x * coarseDims.y));
    const uint ratio = VOLUME_MACROCELL_COARSE / VOLUME_MACROCELL_FINE;
    uvec3 from = macro * ratio, to = min(from + ratio, fineDims);
    float coarseLowest = 3.402823e38, coarseHighest = -3.402823e38, fineSum = 0.0;
    for (uint fz = from.z; fz < to.z; ++fz)
        for (uint fy = from.y; fy < to.y; ++fy)
            for (uint fx = from.x; fx < to.x; ++fx) {
                uvec3 first = uvec3(fx, fy, fz) * VOLUME_MACROCELL_FINE;
                uvec3 last = min(first + VOLUME_MACROCELL_FINE, extent);
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
                float fine = majorantOver(v, data, lowest, highest);
                data.values[v.fineOffset + (fz * fineDims.y + fy) * fineDims.x + fx] = fine;
                fineSum += fine;
                coarseLowest = min(coarseLowest, lowest);
                coarseHighest = max(coarseHighest, highest);
            }
    data.values[v.majorantOffset + cell] = majorantOver(v, data, coarseLowest, coarseHighest);
    SumsRef(params.fineSums).values[cell] = fineSum;
}
