#version 460
// Closest-hit traversal of the two-level 4-wide BVH: one Hit per ray (see traverse.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 0
#define BVH4_COMPRESSED 1  // 8-bit child boxes: faster than full ones on the renderer's rays (README)
#include "traverse.glsl"
