#version 460
// Stage 3b of a bounce (after pt_surface), only in frames whose world has volumes: free-flight sampling.
// Each path ray is delta-tracked through every volume up to the surface it hit (or its tmax); the nearest
// collision over the volumes wins (the extinctions add, so this samples their union exactly), and replaces
// the SurfaceRecord with a medium interaction (MATERIAL_VOLUME: position, albedo) that pt_shade scatters.
// Data-parallel, a rank also runs it on rays visiting from other ranks (params.paths 0, params.mode its
// rank + 1 to key its own random numbers), up to the closest event found so far: the nearest collision
// over the ranks wins, as over the volumes of one rank.
// A march that spends the step budget is parked with what it found so far and continued by the next resume
// round (params.resumeRound > 0: the invocations are the parked marches); one still unfinished after the
// last round flags its record HIT_FLAG_RAN_OUT.
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
    Ray ray = RaysRef(params.rays).rays[i];
    SurfaceRecord r = SurfacesRef(params.surfaces).records[i];
    if ((r.status & ~0xFFu) != 0u) return;  // a flagged traversal: no trustworthy extent
    if (params.resumeRound == 0u) {
        march.t = ray.origin.w;
        march.tEnd = r.status == HIT_FOUND ? r.position.w : ray.direction.w;
    }
    // A path's pixel sample; a ray visiting from another rank (no paths), its index in the visitors' queue.
    PixelSample ps = params.paths != 0ul ? pixelSample(f, PathsRef(params.paths).paths[i].slot)
                                         : PixelSample(i, params.sampleIndex, 0u, false);
    VolumeRng rng = volumeRng(ps.pixel, ps.index, params.bounce, RNG_VOLUME, f.seed ^ (params.mode * 0x9E3779B9u),
                              params.resumeRound);
    VolumeDataRef data = VolumeDataRef(scene.volumeData);
    uint budget = volumeStepBudget();
    bool ranOut = false, parked = false;
    bool collidedHere = false;  // the nearest collision so far was found by this invocation
    uint collisions = 0u;
    uint supersededParked = 0u; // a nearer collision replaced the one a parked march carried (now null)
    for (uint v = march.volume; v < scene.volumeCount; ++v) {
        VolumeRecord volume = VolumesRef(scene.volumes).volumes[v];
        float tStart = v == march.volume ? march.t : ray.origin.w;
        TrackResult track = trackVolume(volume, data, ray.origin.xyz, ray.direction.xyz, tStart, march.tEnd, TRACK_DELTA,
                                        rng, budget);
        collisions += track.collisions;
        if (track.ranOut) {
            march.volume = v;
            march.t = track.t;
            parked = parkMarch(march);
            ranOut = !parked;
            break;
        }
        if (track.transmittance == 0.0 && track.t < march.tEnd) {
            if (march.collidedVolume != 0xFFFFFFFFu && !collidedHere) supersededParked = 1u;
            march.tEnd = track.t;
            march.albedo = vec4(track.albedo, 0.0);
            march.collidedVolume = v;
            collidedHere = true;
        }
    }
    // One real collision per ray (the nearest, counted when its march ends); every other tentative
    // collision counts as null.
    CountersRef counters = CountersRef(f.counters);
    bool collided = march.collidedVolume != 0xFFFFFFFFu;
    const uint real = !parked && collided ? 1u : 0u;
    const uint realHere = collidedHere ? 1u : 0u;
    if (real > 0u) countVolumeSteps(counters.counters, realCollisions, 1u);
    const uint nulls = collisions - realHere + supersededParked;
    if (nulls > 0u) countVolumeSteps(counters.counters, nullCollisions, nulls);
    if (parked) return;
    if (ranOut) {
        SurfacesRef(params.surfaces).records[i].status = r.status | HIT_FLAG_RAN_OUT;
        return;
    }
    if (!collided) return;
    VolumeRecord hitVolume = VolumesRef(scene.volumes).volumes[march.collidedVolume];
    r.status = HIT_FOUND;
    r.position = vec4(ray.origin.xyz + march.tEnd * ray.direction.xyz, march.tEnd);
    r.geometricNormal = vec4(0.0, 0.0, 0.0, 1.0);  // opaque: a collision always scatters
    r.shadingNormal = vec4(0.0);                    // not a light
    r.baseColor = vec4(clamp(march.albedo.rgb, vec3(0.0), vec3(1.0)), 0.0);
    r.emission = vec4(0.0);
    r.layers = vec4(0.0, 0.0, 1.0, 1.0);
    r.materialKind = MATERIAL_VOLUME;
    r.f0 = 0.0;
    r.primitiveId = 0xFFFFFFFFu;
    r.objectId = hitVolume.objectId;
    r.instanceId = hitVolume.instanceId;
    SurfacesRef(params.surfaces).records[i] = r;
}
