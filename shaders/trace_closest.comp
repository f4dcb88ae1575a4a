#version 460
// Closest-hit traversal of the two-level BVH: one Hit per ray (see traverse.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 0
#include "traverse.glsl"
