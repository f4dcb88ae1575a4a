#version 460
// The field of an unstructured mesh at given grid-space points, as the tracking kernels find it
// (shaders/unstructured.glsl): tests/unit/unstructured_test.cpp compares it with the exact interpolant.
// The result's x is 2 where the walk from the start cell's tetrahedron found the point, 1 where only the BVH
// did, 0 where neither did.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#define INFINITY uintBitsToFloat(0x7f800000u)
#include "unstructured.glsl"

layout(local_size_x = 64) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer PointsRef { vec4 points[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer ResultsRef { vec2 results[]; };

layout(push_constant) uniform Params {
    uint64_t mesh;
    uint64_t points;
    uint64_t results;
    uint count;
} params;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    UnstructuredHeader h = unstructuredHeader(params.mesh);
    vec3 p = PointsRef(params.points).points[i].xyz;
    float value;
    bool walked = unstructuredWalk(params.mesh, MeshWordsRef(params.mesh), h, p, unstructuredStartIndex(h, p), value);
    bool found = unstructuredValue(params.mesh, h, p, value);
    ResultsRef(params.results).results[i] = vec2(found ? (walked ? 2.0 : 1.0) : 0.0, value);
}
