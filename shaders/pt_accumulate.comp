#version 460
// End of a sample pass: each of the pass's samples of a pixel joins the pixel's running sum, in the order of
// their index (the same sum as one pass per sample), unless it is NaN or Inf, in which case it is counted and
// dropped (the pixel's own sample count keeps its average unbiased by the drop).
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"

void main() {
    if (gl_GlobalInvocationID.x >= params.count) return;
    uint pixel = params.firstPixel + gl_GlobalInvocationID.x;
    FrameConstants f = FrameRef(params.frame).frame;
    uint pixels = f.width * f.height;
    uint samples = min(f.passSamples, f.latestSample + 1u - params.sampleIndex);
    vec4 sum = Vec4sRef(f.accumulation).values[pixel];
    uint accepted = UintsRef(f.sampleCount).values[pixel];
    for (uint k = 0u; k < samples; ++k) {
        vec4 sampleValue = Vec4sRef(f.sampleRadiance).values[k * pixels + pixel];
        if (!allFinite(sampleValue)) {
            atomicAdd(CountersRef(f.counters).counters.nonFinite, 1u);
            continue;
        }
        sum += sampleValue;
        ++accepted;
    }
    Vec4sRef(f.accumulation).values[pixel] = sum;
    UintsRef(f.sampleCount).values[pixel] = accepted;
}
