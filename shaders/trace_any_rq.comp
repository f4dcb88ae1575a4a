#version 460
// Any-hit (occlusion) ray-query traversal: one status word per ray (see traverse_rq.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 1
#include "traverse_rq.glsl"
