#version 460
// Any-hit (occlusion) traversal of a single-level 4-wide triangle BVH: one status word per ray (see
// traverse_bvh4.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 1
#define BVH4_COMPRESSED 0
#include "traverse_bvh4.glsl"
