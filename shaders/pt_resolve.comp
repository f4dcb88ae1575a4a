#version 460
// The color channel from the accumulation: the average of each pixel's accepted samples, written as
// Rgba8Unorm (clamped), Rgba8Srgb (sRGB-encoded color, linear alpha) or Rgba32Float. Row 0 is the bottom.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"

float linearToSrgb(float c) {
    c = clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

void main() {
    if (gl_GlobalInvocationID.x >= params.count) return;
    uint pixel = params.firstPixel + gl_GlobalInvocationID.x;
    FrameConstants f = FrameRef(params.frame).frame;
    uint samples = UintsRef(f.sampleCount).values[pixel];
    vec4 average = samples > 0u ? Vec4sRef(f.accumulation).values[pixel] / float(samples) : vec4(0.0);
    if (params.mode == OUTPUT_RGBA32_FLOAT) {
        Vec4sRef(params.results).values[pixel] = average;
    } else {
        if (params.mode == OUTPUT_RGBA8_SRGB)
            average.rgb = vec3(linearToSrgb(average.r), linearToSrgb(average.g), linearToSrgb(average.b));
        UintsRef(params.results).values[pixel] = packUnorm4x8(average);
    }
}
