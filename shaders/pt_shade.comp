#version 460
// Stage 4 of a bounce, run at each path's home rank from the SurfaceRecord that pt_surface packed at the
// hit (no scene geometry or textures are read here, only lights): a miss adds the background (camera
// rays) or the ambient light (secondary rays); a hit adds its emission, passes through a transparent
// surface with probability 1 - opacity, requests one shadow ray toward a uniformly chosen light
// (next-event estimation), and samples the BSDF for the next ray, with Russian roulette from the third
// interaction on. Survivors are appended to the next queue and shadow requests to the shadow queue, each
// by an atomic counter.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"
#include "bsdf.glsl"
#include "lights.glsl"

// Russian roulette starts once a path has had this many surface interactions.
const uint ROULETTE_FROM_DEPTH = 3u;

SurfaceMaterial surfaceMaterial(SurfaceRecord r) {
    SurfaceMaterial m;
    m.kind = r.materialKind;
    m.baseColor = r.baseColor.rgb;
    m.metallic = r.baseColor.w;
    m.alpha = r.emission.w;
    m.f0 = r.f0;
    return m;
}

// Queue appends. A queue never holds more entries than the queue being shaded (each path appends at most
// one of each), so the bound check only keeps a bug from writing out of range.
void appendPath(Ray ray, PathState path) {
    CountersRef c = CountersRef(FrameRef(params.frame).frame.counters);
    uint slot = atomicAdd(c.counters.nextPaths, 1u);
    if (slot >= params.count) return;
    RaysRef(params.nextRays).rays[slot] = ray;
    PathsRef(params.nextPaths).paths[slot] = path;
}

void appendShadow(Ray ray, vec3 contribution, uint pixel) {
    CountersRef c = CountersRef(FrameRef(params.frame).frame.counters);
    uint slot = atomicAdd(c.counters.shadowRays, 1u);
    if (slot >= params.count) return;
    RaysRef(params.shadowRays).rays[slot] = ray;
    ShadowRequestsRef(params.shadowRequests).requests[slot] = ShadowRequest(vec4(contribution, 0.0), pixel, 0u, 0u, 0u);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    FrameConstants f = FrameRef(params.frame).frame;
    SceneDesc scene = SceneRef(params.scene).desc;
    Ray ray = RaysRef(params.rays).rays[i];
    SurfaceRecord r = SurfacesRef(params.surfaces).records[i];
    PathState path = PathsRef(params.paths).paths[i];
    Vec4sRef radiance = Vec4sRef(f.sampleRadiance);
    bool camera = (path.flags & PATH_FLAG_CAMERA) != 0u;
    uint passThroughs = path.flags >> PATH_PASS_THROUGH_SHIFT;

    if ((r.status & ~0xFFu) != 0u) atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
    if (r.status != HIT_FOUND) {  // a miss, or a flagged traversal treated as one
        if (camera) radiance.values[path.pixel] += vec4(path.throughput.rgb * f.background.rgb, f.background.a);
        else radiance.values[path.pixel].rgb += path.throughput.rgb * f.ambient.rgb;
        return;
    }
    if (camera && passThroughs == 0u && f.depth != 0ul) FloatsRef(f.depth).values[path.pixel] = r.position.w;

    vec3 position = r.position.xyz;
    vec3 geometricNormal = r.geometricNormal.xyz;
    vec3 wo = -normalize(ray.direction.xyz);
    vec4 uLight = random4(path.pixel, params.sampleIndex, params.bounce, RNG_LIGHT, f.seed);

    // Transparency: continue straight on, unchanged, with probability 1 - opacity.
    if (uLight.w >= r.geometricNormal.w) {
        if (passThroughs >= PATH_MAX_PASS_THROUGHS) return;
        path.flags += 1u << PATH_PASS_THROUGH_SHIFT;
        appendPath(Ray(vec4(offsetRayOrigin(position, -geometricNormal), 0.0), vec4(ray.direction.xyz, INFINITY)), path);
        return;
    }
    if (camera) radiance.values[path.pixel].a = 1.0;
    radiance.values[path.pixel].rgb += path.throughput.rgb * r.emission.rgb;

    SurfaceMaterial m = surfaceMaterial(r);
    vec3 n = r.shadingNormal.xyz;
    if (dot(n, wo) <= 0.0) n = geometricNormal;  // interpolated normals can face away from the viewer
    vec3 up = offsetRayOrigin(position, geometricNormal);

    // Next-event estimation: one light, chosen uniformly (pdf 1 / lightCount).
    if (scene.lightCount > 0u) {
        uint chosen = min(uint(uLight.x * float(scene.lightCount)), scene.lightCount - 1u);
        LightSample ls;
        if (sampleLight(LightsRef(scene.lights).lights[chosen], position, uLight.yz, ls) &&
            dot(ls.direction, geometricNormal) > 0.0) {
            float pdf;
            vec3 contribution = path.throughput.rgb * evalBsdf(m, n, wo, ls.direction, pdf) * ls.incident *
                                float(scene.lightCount);
            // Stop just short of the light, so geometry at the light itself does not shadow it.
            float tmax = isinf(ls.distance) ? INFINITY : ls.distance * (1.0 - 1e-4);
            if (maxComponent(contribution) > 0.0)
                appendShadow(Ray(vec4(up, 0.0), vec4(ls.direction, tmax)), contribution, path.pixel);
        }
    }

    uint depth = path.depth + 1u;
    if (depth >= f.maxPathLength) return;
    vec4 uBsdf = random4(path.pixel, params.sampleIndex, params.bounce, RNG_BSDF, f.seed);
    vec3 wi;
    vec3 weight;
    if (!sampleBsdf(m, n, wo, uBsdf.xyz, wi, weight)) return;
    if (dot(wi, geometricNormal) <= 0.0) return;  // below the true surface: the path ends
    vec3 throughput = path.throughput.rgb * weight;
    if (depth >= ROULETTE_FROM_DEPTH) {
        float survive = min(maxComponent(throughput), 0.95);
        if (uBsdf.w >= survive) return;
        throughput /= survive;
    }
    if (!(maxComponent(throughput) > 0.0)) return;
    appendPath(Ray(vec4(up, 0.0), vec4(wi, INFINITY)), PathState(vec4(throughput, 0.0), path.pixel, depth, path.flags & ~PATH_FLAG_CAMERA, 0u));
}
