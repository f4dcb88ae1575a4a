#version 460
// Stage 4 of a bounce (after the any-hit trace of the shadow queue): each shadow ray that reached its
// light adds its contribution to its pixel sample. A pixel sample has at most one shadow ray per bounce, so
// the additions never race.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= stageCount()) return;
    FrameConstants f = FrameRef(params.frame).frame;
    uint occlusion = UintsRef(params.results).values[i];
    if ((occlusion & ~0xFFu) != 0u) atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
    if (occlusion == HIT_FOUND) return;  // occluded; a flagged traversal counts as unoccluded (a miss)
    ShadowRequest request = ShadowRequestsRef(params.shadowRequests).requests[i];
    Vec4sRef(f.sampleRadiance).values[request.slot].rgb += request.contribution.rgb;
}
