// What every path tracing stage (pt_*.comp) shares: the parameter block, buffer views of the frame, the
// scene and the queues, and the workgroup size (specialization constant 0, set by the host).
#ifndef RIPPLE_PT_COMMON_GLSL
#define RIPPLE_PT_COMMON_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/material.h"
#include "shared/path.h"
#include "shared/ray.h"
#include "shared/scene.h"

layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push { StageParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer FrameRef { FrameConstants frame; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneRef { SceneDesc desc; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer PathsRef { PathState paths[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer SurfacesRef { SurfaceRecord records[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ShadowRequestsRef { ShadowRequest requests[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4sRef { vec4 values[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer FloatsRef { float values[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer UintsRef { uint values[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer CountersRef { PathCounters counters; };

#define INFINITY uintBitsToFloat(0x7f800000u)

// Items this dispatch processes: StageParams.count, or a queue length pt_queue_advance left on the device.
uint stageCount() {
    if (params.countSource == COUNT_FROM_PARAMS) return params.count;
    CountersRef c = CountersRef(FrameRef(params.frame).frame.counters);
    return params.countSource == COUNT_PATH_QUEUE ? c.counters.pathCount : c.counters.shadowCount;
}

bool allFinite(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

// The pixel sample behind a slot of the pass (PathState::slot). A frame of few pixels traces several of
// each pixel's samples in one pass (PathTracer::render): slot k * width * height + pixel is the pixel's
// sample sampleIndex + k. Random numbers are keyed by the pixel and that index, so the image is the same
// bit for bit however many samples a pass holds.
struct PixelSample {
    uint pixel;       // y * width + x, row 0 at the bottom
    uint index;       // the sample, counted over all render() calls
    uint stratified;  // its point in the pixel's stratified sequences (StageParams::stratifiedSample)
    bool latest;      // the render()'s last sample: the one depth and the surface channels show
};

PixelSample pixelSample(FrameConstants f, uint slot) {
    uint pixels = f.width * f.height;
    uint k = slot / pixels;
    uint index = params.sampleIndex + k;
    return PixelSample(slot - k * pixels, index, params.stratifiedSample + (k << 1u), index == f.latestSample);
}

#endif
