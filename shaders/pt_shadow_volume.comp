#version 460
// Before pt_shadow_resolve, only in frames whose world has volumes: each shadow request's contribution is
// multiplied by the transmittance of the volumes along its ray, estimated by ratio tracking (unbiased).
// A march that spends the step budget is parked and continued by the next resume round, as in pt_volume;
// one still unfinished after the last round adds nothing and is counted as flagged. Data-parallel, a rank also
// runs it on shadow rays visiting from other ranks (params.shadowRequests 0, params.mode its rank + 1):
// the transmittance is written to params.results (a float per ray) for the wire to carry home.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"
#include "intersect.glsl"
#include "volume.glsl"

void main() {
    FrameConstants f = FrameRef(params.frame).frame;
    SceneDesc scene = SceneRef(params.scene).desc;
    if (scene.volumeCount == 0u) return;
    // Where the march starts: the item's own ray from its start, or a parked march where it stopped.
    VolumeParked march = VolumeParked(gl_GlobalInvocationID.x, 0u, 0.0, 0.0, vec4(0.0), 1.0, 0xFFFFFFFFu, 0u, 0u);
    if (params.resumeRound == 0u) {
        if (march.ray >= stageCount()) return;
    } else if (!parkedMarch(march)) {
        return;
    }
    uint i = march.ray;
    Ray ray = RaysRef(params.shadowRays).rays[i];
    if (params.resumeRound == 0u) march.t = ray.origin.w;
    bool visiting = params.shadowRequests == 0ul;
    PixelSample ps = visiting ? PixelSample(i, params.sampleIndex, 0u, false)
                              : pixelSample(f, ShadowRequestsRef(params.shadowRequests).requests[i].slot);
    VolumeRng rng = volumeRng(ps.pixel, ps.index, params.bounce, RNG_VOLUME_SHADOW,
                              f.seed ^ (params.mode * 0x9E3779B9u), params.resumeRound);
    VolumeDataRef data = VolumeDataRef(scene.volumeData);
    uint budget = volumeStepBudget();
    uint collisions = 0u;
    bool parked = false;
    for (uint v = march.volume; v < scene.volumeCount && march.transmittance > 0.0; ++v) {
        VolumeRecord volume = VolumesRef(scene.volumes).volumes[v];
        float tStart = v == march.volume ? march.t : ray.origin.w;
        TrackResult track = trackVolume(volume, data, ray.origin.xyz, ray.direction.xyz, tStart, ray.direction.w,
                                        TRACK_RATIO, rng, budget);
        march.transmittance *= track.transmittance;
        collisions += track.collisions;
        if (track.ranOut) {
            march.volume = v;
            march.t = track.t;
            parked = parkMarch(march);
            if (!parked) {
                atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
                march.transmittance = 0.0;
            }
            break;
        }
    }
    if (collisions > 0u) countVolumeSteps(CountersRef(f.counters).counters, ratioCollisions, collisions);
    if (parked) return;
    if (visiting) FloatsRef(params.results).values[i] = march.transmittance;
    else ShadowRequestsRef(params.shadowRequests).requests[i].contribution.rgb *= march.transmittance;
}
