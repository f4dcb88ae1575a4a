#version 460
// Before pt_shadow_resolve, only in frames whose world has volumes: each shadow request's contribution is
// multiplied by the transmittance of the volumes along its ray, estimated by ratio tracking (unbiased).
// A ray whose tracking ran out of budget adds nothing and is counted as flagged.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"
#include "intersect.glsl"
#include "volume.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= stageCount()) return;
    FrameConstants f = FrameRef(params.frame).frame;
    SceneDesc scene = SceneRef(params.scene).desc;
    if (scene.volumeCount == 0u) return;
    Ray ray = RaysRef(params.shadowRays).rays[i];
    ShadowRequest request = ShadowRequestsRef(params.shadowRequests).requests[i];
    VolumeRng rng = volumeRng(request.pixel, params.sampleIndex, params.bounce, RNG_VOLUME_SHADOW, f.seed);
    VolumeDataRef data = VolumeDataRef(scene.volumeData);
    float transmittance = 1.0;
    for (uint v = 0u; v < scene.volumeCount && transmittance > 0.0; ++v) {
        VolumeRecord volume = VolumesRef(scene.volumes).volumes[v];
        TrackResult track = trackVolume(volume, data, ray.origin.xyz, ray.direction.xyz, ray.origin.w, ray.direction.w,
                                        TRACK_RATIO, rng);
        if (track.ranOut) {
            atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
            transmittance = 0.0;
        }
        transmittance *= track.transmittance;
    }
    ShadowRequestsRef(params.shadowRequests).requests[i].contribution.rgb = request.contribution.rgb * transmittance;
}
