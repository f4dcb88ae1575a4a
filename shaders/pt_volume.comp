#version 460
// Stage 3b of a bounce (after pt_surface), only in frames whose world has volumes: free-flight sampling.
// Each path ray is delta-tracked through every volume up to the surface it hit (or its tmax); the nearest
// collision over the volumes wins (the extinctions add, so this samples their union exactly), and replaces
// the SurfaceRecord with a medium interaction (MATERIAL_VOLUME: position, albedo) that pt_shade scatters.
// Data-parallel, a rank also runs it on rays visiting from other ranks (params.paths 0, params.mode its
// rank + 1 to key its own random numbers), up to the closest event found so far: the nearest collision
// over the ranks wins, as over the volumes of one rank.
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
    Ray ray = RaysRef(params.rays).rays[i];
    SurfaceRecord r = SurfacesRef(params.surfaces).records[i];
    float tEnd = r.status == HIT_FOUND ? r.position.w : ray.direction.w;
    if ((r.status & ~0xFFu) != 0u) return;  // a flagged traversal: no trustworthy extent
    uint key = params.paths != 0ul ? PathsRef(params.paths).paths[i].pixel : i;
    VolumeRng rng = volumeRng(key, params.sampleIndex, params.bounce, RNG_VOLUME, f.seed ^ (params.mode * 0x9E3779B9u));
    VolumeDataRef data = VolumeDataRef(scene.volumeData);
    bool collided = false;
    bool ranOut = false;
    vec3 albedo = vec3(0.0);
    uint objectId = 0xFFFFFFFFu, instanceId = 0xFFFFFFFFu;
    uint collisions = 0u;
    for (uint v = 0u; v < scene.volumeCount; ++v) {
        VolumeRecord volume = VolumesRef(scene.volumes).volumes[v];
        TrackResult track = trackVolume(volume, data, ray.origin.xyz, ray.direction.xyz, ray.origin.w, tEnd, TRACK_DELTA, rng);
        ranOut = ranOut || track.ranOut;
        collisions += track.collisions;
        if (track.transmittance == 0.0 && track.t < tEnd) {
            tEnd = track.t;
            albedo = track.albedo;
            objectId = volume.objectId;
            instanceId = volume.instanceId;
            collided = true;
        }
    }
    // One real collision (the nearest, if any); every other tentative collision counts as null.
    CountersRef counters = CountersRef(f.counters);
    const uint real = collided ? 1u : 0u;
    if (collided) countVolumeSteps(counters.counters, realCollisions, 1u);
    if (collisions > real) countVolumeSteps(counters.counters, nullCollisions, collisions - real);
    if (ranOut) {
        SurfacesRef(params.surfaces).records[i].status = r.status | HIT_FLAG_RAN_OUT;
        return;
    }
    if (!collided) return;
    r.status = HIT_FOUND;
    r.position = vec4(ray.origin.xyz + tEnd * ray.direction.xyz, tEnd);
    r.geometricNormal = vec4(0.0, 0.0, 0.0, 1.0);  // opaque: a collision always scatters
    r.shadingNormal = vec4(0.0);                    // not a light
    r.baseColor = vec4(clamp(albedo, vec3(0.0), vec3(1.0)), 0.0);
    r.emission = vec4(0.0);
    r.layers = vec4(0.0, 0.0, 1.0, 1.0);
    r.materialKind = MATERIAL_VOLUME;
    r.f0 = 0.0;
    r.primitiveId = 0xFFFFFFFFu;
    r.objectId = objectId;
    r.instanceId = instanceId;
    SurfacesRef(params.surfaces).records[i] = r;
}
