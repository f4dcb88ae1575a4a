#version 460
// After pt_surface on the first bounce, at each path's home: the albedo, normal and id channels of the
// pixel from the SurfaceRecord of its camera ray (only the channels asked for have a buffer). Like depth,
// they describe the first surface the camera ray met, transparent or not, in the latest sample.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "shared/channels.h"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ChannelsRef { ChannelBuffers channels; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= stageCount()) return;
    PathState path = PathsRef(params.paths).paths[i];
    if ((path.flags & PATH_FLAG_CAMERA) == 0u || ((path.flags >> PATH_PASS_THROUGH_SHIFT) & 0xFFu) != 0u) return;
    PixelSample ps = pixelSample(FrameRef(params.frame).frame, path.slot);
    if (!ps.latest) return;
    SurfaceRecord r = SurfacesRef(params.surfaces).records[i];
    if (r.status != HIT_FOUND) return;  // pt_generate left the miss values
    ChannelBuffers c = ChannelsRef(params.results).channels;
    if (c.albedo != 0ul) Vec4sRef(c.albedo).values[ps.pixel] = vec4(r.baseColor.rgb, 0.0);
    if (c.normal != 0ul) Vec4sRef(c.normal).values[ps.pixel] = vec4(r.shadingNormal.xyz, 0.0);
    if (c.primitiveId != 0ul) UintsRef(c.primitiveId).values[ps.pixel] = r.primitiveId;
    if (c.objectId != 0ul) UintsRef(c.objectId).values[ps.pixel] = r.objectId;
    if (c.instanceId != 0ul) UintsRef(c.instanceId).values[ps.pixel] = r.instanceId;
}
