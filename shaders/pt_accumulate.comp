#version 460
// End of a sample pass: each pixel's sample joins the running sum, unless it is NaN or Inf, in which case
// it is counted and dropped (the pixel's own sample count keeps its average unbiased by the drop).
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"

void main() {
    if (gl_GlobalInvocationID.x >= params.count) return;
    uint pixel = params.firstPixel + gl_GlobalInvocationID.x;
    FrameConstants f = FrameRef(params.frame).frame;
    vec4 sampleValue = Vec4sRef(f.sampleRadiance).values[pixel];
    if (!allFinite(sampleValue)) {
        atomicAdd(CountersRef(f.counters).counters.nonFinite, 1u);
        return;
    }
    Vec4sRef(f.accumulation).values[pixel] += sampleValue;
    UintsRef(f.sampleCount).values[pixel] += 1u;
}
