// Push constants of every trace kernel (software BVH4 and ray-query back-ends alike) and the number of
// rays a dispatch covers.
#ifndef RIPPLE_TRACE_PARAMS_GLSL
#define RIPPLE_TRACE_PARAMS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/ray.h"

layout(push_constant) uniform Push { TraceParams params; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RayCountRef { uint rayCount; };

// Rays in this dispatch: from the push constants, or written on the device by the stage before.
uint traceRayCount() {
    return params.rayCountAddress != 0ul ? RayCountRef(params.rayCountAddress).rayCount : params.rayCount;
}

#endif
