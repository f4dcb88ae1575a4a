#version 460
// Stage 1 of a sample pass: one camera ray per pixel of the wave (perspective or orthographic, through
// the image region, jittered within the pixel), a fresh path state beside it, and the pixel's sample
// radiance and depth cleared.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    FrameConstants f = FrameRef(params.frame).frame;
    uint pixel = params.firstPixel + i;
    uvec2 xy = uvec2(pixel % f.width, pixel / f.width);  // row 0 is the bottom row

    vec2 jitter = random4(pixel, params.sampleIndex, 0u, RNG_CAMERA, f.seed).xy;
    vec2 onImage = (vec2(xy) + jitter) / vec2(f.width, f.height);
    vec2 screen = mix(f.imageRegion.xy, f.imageRegion.zw, onImage);
    vec2 centered = 2.0 * screen - 1.0;  // [-1, 1] over the screen

    vec3 origin;
    vec3 direction;
    float aspect = f.cameraRight.w;
    if (floatBitsToUint(f.cameraPosition.w) == CAMERA_ORTHOGRAPHIC) {
        float halfHeight = 0.5 * f.cameraForward.w;
        origin = f.cameraPosition.xyz + centered.x * halfHeight * aspect * f.cameraRight.xyz +
                 centered.y * halfHeight * f.cameraUp.xyz;
        direction = f.cameraForward.xyz;
    } else {
        float tanHalf = f.cameraForward.w;
        origin = f.cameraPosition.xyz;
        direction = normalize(f.cameraForward.xyz + centered.x * tanHalf * aspect * f.cameraRight.xyz +
                              centered.y * tanHalf * f.cameraUp.xyz);
    }
    RaysRef(params.rays).rays[i] = Ray(vec4(origin, 0.0), vec4(direction, INFINITY));
    PathsRef(params.paths).paths[i] = PathState(vec4(1.0), pixel, 0u, PATH_FLAG_CAMERA, 0u);
    Vec4sRef(f.sampleRadiance).values[pixel] = vec4(0.0);
    if (f.depth != 0ul) FloatsRef(f.depth).values[pixel] = INFINITY;
}
