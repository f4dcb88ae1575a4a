#version 460
// The field of an AMR hierarchy at given grid-space points, as the tracking kernels find it
// (shaders/amr.glsl): tests/unit/amr_test.cpp compares it with the finest covering cell's value.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "amr.glsl"

layout(local_size_x = 64) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer PointsRef { vec4 points[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer ResultsRef { vec2 results[]; };

layout(push_constant) uniform Params {
    uint64_t amr;
    uint64_t points;
    uint64_t results;
    uint count;
    uint macroX;
    uint macroY;
    uint macroZ;
} params;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    float value;
    bool found = amrValue(params.amr, uvec3(params.macroX, params.macroY, params.macroZ), PointsRef(params.points).points[i].xyz, value);
    ResultsRef(params.results).results[i] = vec2(found ? 1.0 : 0.0, value);
}
