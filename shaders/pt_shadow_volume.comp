#version 460
// Before pt_shadow_resolve, only in frames whose world has volumes: each shadow request's contribution is
// multiplied by the transmittance of the volumes along its ray, estimated by ratio tracking (unbiased).
// A ray whose tracking ran out of budget adds nothing and is counted as flagged. Data-parallel, a rank also
// runs it on shadow rays visiting from other ranks (params.shadowRequests 0, params.mode its rank + 1):
// the transmittance is written to params.results (a float per ray) for the wire to carry home.
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
    bool visiting = params.shadowRequests == 0ul;
    uint key = visiting ? i : ShadowRequestsRef(params.shadowRequests).requests[i].pixel;
    VolumeRng rng = volumeRng(key, params.sampleIndex, params.bounce, RNG_VOLUME_SHADOW, f.seed ^ (params.mode * 0x9E3779B9u));
    VolumeDataRef data = VolumeDataRef(scene.volumeData);
    float transmittance = 1.0;
    uint collisions = 0u;
    for (uint v = 0u; v < scene.volumeCount && transmittance > 0.0; ++v) {
        VolumeRecord volume = VolumesRef(scene.volumes).volumes[v];
        TrackResult track = trackVolume(volume, data, ray.origin.xyz, ray.direction.xyz, ray.origin.w, ray.direction.w,
                                        TRACK_RATIO, rng);
        if (track.ranOut) {
            atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
            transmittance = 0.0;
        }
        transmittance *= track.transmittance;
        collisions += track.collisions;
    }
    if (collisions > 0u) countVolumeSteps(CountersRef(f.counters).counters, ratioCollisions, collisions);
    if (visiting) FloatsRef(params.results).values[i] = transmittance;
    else ShadowRequestsRef(params.shadowRequests).requests[i].contribution.rgb *= transmittance;
}
