#version 460
// Any-hit (occlusion) traversal of the two-level BVH: one status word per ray (see traverse.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 1
#include "traverse.glsl"
