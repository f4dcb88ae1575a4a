#version 460
// Stage 1 of a sample pass: one camera ray per sample slot of the wave (perspective with an optional thin
// lens, orthographic, or omnidirectional equirectangular, through the image region, jittered within the
// pixel by a stratified sequence), a fresh path state beside it, and the slot's sample radiance cleared; the
// render()'s last sample also clears its pixel's depth and surface channels.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"
#include "shared/channels.h"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ChannelsRef { ChannelBuffers channels; };

const float PI = 3.14159265358979;

// Uniform point on the unit disk (polar mapping: area-preserving, which is all a lens needs).
vec2 uniformDisk(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return r * vec2(cos(phi), sin(phi));
}

void clearChannels(uint pixel) {
    if (params.results == 0ul) return;
    ChannelBuffers c = ChannelsRef(params.results).channels;
    if (c.albedo != 0ul) Vec4sRef(c.albedo).values[pixel] = vec4(0.0);
    if (c.normal != 0ul) Vec4sRef(c.normal).values[pixel] = vec4(0.0);
    if (c.primitiveId != 0ul) UintsRef(c.primitiveId).values[pixel] = 0xFFFFFFFFu;
    if (c.objectId != 0ul) UintsRef(c.objectId).values[pixel] = 0xFFFFFFFFu;
    if (c.instanceId != 0ul) UintsRef(c.instanceId).values[pixel] = 0xFFFFFFFFu;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    FrameConstants f = FrameRef(params.frame).frame;
    uint slot = params.firstPixel + i;
    PixelSample ps = pixelSample(f, slot);
    uint pixel = ps.pixel;
    uvec2 xy = uvec2(pixel % f.width, pixel / f.width);  // row 0 is the bottom row

    vec4 u = random4(pixel, ps.index, 0u, RNG_CAMERA, f.seed);
    vec2 jitter = stratified2D(pixel, ps.stratified, RNG_CAMERA_JITTER, f.seed);
    vec2 onImage = (vec2(xy) + jitter) / vec2(f.width, f.height);
    vec2 screen = mix(f.imageRegion.xy, f.imageRegion.zw, onImage);
    vec2 centered = 2.0 * screen - 1.0;  // [-1, 1] over the screen

    vec3 origin = f.cameraPosition.xyz;
    vec3 direction;
    uint kind = floatBitsToUint(f.cameraPosition.w);
    if (kind == CAMERA_ORTHOGRAPHIC) {
        origin += centered.x * f.cameraRight.xyz + centered.y * f.cameraUp.xyz;
        direction = f.cameraForward.xyz;
    } else if (kind == CAMERA_OMNIDIRECTIONAL) {
        // Longitude across the width (the centre looks along forward), latitude up the height.
        float longitude = (screen.x - 0.5) * 2.0 * PI;
        float latitude = (screen.y - 0.5) * PI;
        direction = cos(latitude) * (sin(longitude) * f.cameraRight.xyz + cos(longitude) * f.cameraForward.xyz) +
                    sin(latitude) * f.cameraUp.xyz;
    } else {
        direction = f.cameraForward.xyz + centered.x * f.cameraRight.xyz + centered.y * f.cameraUp.xyz;
        float aperture = f.cameraForward.w;
        if (aperture > 0.0) {
            // Thin lens: start on the lens disk and aim at the point this pixel sees on the plane in focus.
            vec2 lens = aperture * uniformDisk(u.zw);
            vec3 offset = lens.x * normalize(f.cameraRight.xyz) + lens.y * normalize(f.cameraUp.xyz);
            direction = f.cameraRight.w * direction - offset;
            origin += offset;
        }
        direction = normalize(direction);
    }
    // Near and far clip planes along forward: distances along this ray, whose direction is unit (or forward).
    float tmin = 0.0, tmax = INFINITY;
    if (kind != CAMERA_OMNIDIRECTIONAL) {
        float along = dot(direction, f.cameraForward.xyz);
        if (along > 0.0) {
            tmin = f.cameraUp.w / along;
            tmax = f.cameraFar / along;
        }
    }
    RaysRef(params.rays).rays[i] = Ray(vec4(origin, tmin), vec4(direction, tmax));
    PathsRef(params.paths).paths[i] = PathState(vec4(1.0), slot, PATH_FLAG_CAMERA, 0.0, 0.0);
    Vec4sRef(f.sampleRadiance).values[slot] = vec4(0.0);
    if (!ps.latest) return;
    if (f.depth != 0ul) FloatsRef(f.depth).values[pixel] = INFINITY;
    clearChannels(pixel);
}
