#version 460
// Closest-hit ray-query traversal: one Hit per ray (see traverse_rq.glsl).
#extension GL_GOOGLE_include_directive : require
#define TRACE_ANY_HIT 0
#include "traverse_rq.glsl"
