#version 460
// Stage 4 of a bounce, run at each path's home rank from the SurfaceRecord that pt_surface packed at the
// hit (no scene geometry is read here, only lights and the BSDF tables). A BSDF-sampled ray first collects
// the quad, ring and hdri lights it passed (MIS-weighted); then a miss adds the background (camera rays)
// or the ambient light (MIS-weighted); a hit adds its emission (MIS-weighted where it is a light), passes
// through a transparent surface with probability 1 - opacity, requests one shadow ray toward the ambient
// light or a light picked in proportion to power (next-event estimation, MIS-weighted), and samples the
// BSDF for the next ray, with Russian roulette from the third interaction on. Survivors are appended to
// the next queue and shadow requests to the shadow queue, each by an atomic counter. The eyeLight
// renderer's quick look ends at the first interaction instead (SHADING_EYE_LIGHT).
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "rng.glsl"
#include "bsdf.glsl"
#include "texture.glsl"
#include "lights.glsl"

// Russian roulette starts once a path has had this many surface interactions.
const uint ROULETTE_FROM_DEPTH = 3u;
// The Henyey-Greenstein phase function of mean cosine g, at the cosine between the direction light
// travelled before and after scattering; it is also the pdf of samplePhase. g = 0: isotropic, 1 / (4 pi).
float phaseHG(float cosTheta, float g) {
    float denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * PI * denom * sqrt(max(denom, 1e-12)));
}

// A direction scattered from `forward` with density phaseHG (inverting its CDF in the cosine).
vec3 samplePhase(vec3 forward, float g, vec2 u) {
    float cosTheta;
    if (abs(g) < 1e-3) {  // the host sends 0 for these (PathTracer.cpp)
        cosTheta = 1.0 - 2.0 * u.x;
    } else {
        float s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        cosTheta = clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
    }
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = 2.0 * PI * u.y;
    vec3 t = normalize(abs(forward.x) > 0.5 ? cross(forward, vec3(0.0, 1.0, 0.0)) : cross(forward, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(forward, t);
    return normalize(sinTheta * (cos(phi) * t + sin(phi) * b) + cosTheta * forward);
}

SurfaceMaterial surfaceMaterial(SurfaceRecord r, SceneDesc scene) {
    SurfaceMaterial m;
    m.kind = r.materialKind;
    m.baseColor = r.baseColor.rgb;
    m.metallic = r.baseColor.w;
    m.alpha = r.emission.w;
    m.f0 = r.f0;
    m.transmission = r.layers.x;
    m.clearcoat = r.layers.y;
    m.clearcoatAlpha = r.layers.z;
    m.eta = r.layers.w;
    m.texels = scene.texels;
    m.tableOffset = scene.bsdfTables;
    return m;
}

// The optional radiance clamp (FrameConstants.maxRadiance).
vec3 clamped(FrameConstants f, vec3 c) {
    float largest = maxComponent(c);
    return f.maxRadiance > 0.0 && largest > f.maxRadiance ? c * (f.maxRadiance / largest) : c;
}

// Queue appends. A queue never holds more entries than the queue being shaded (each path appends at most
// one of each), so the bound check only keeps a bug from writing out of range.
void appendPath(Ray ray, PathState path) {
    CountersRef c = CountersRef(FrameRef(params.frame).frame.counters);
    uint entry = atomicAdd(c.counters.nextPaths, 1u);
    if (entry >= stageCount()) return;
    RaysRef(params.nextRays).rays[entry] = ray;
    PathsRef(params.nextPaths).paths[entry] = path;
}

void appendShadow(Ray ray, vec3 contribution, uint slot) {
    CountersRef c = CountersRef(FrameRef(params.frame).frame.counters);
    uint entry = atomicAdd(c.counters.shadowRays, 1u);
    if (entry >= stageCount()) return;
    RaysRef(params.shadowRays).rays[entry] = ray;
    ShadowRequestsRef(params.shadowRequests).requests[entry] = ShadowRequest(vec4(contribution, 0.0), slot, 0u, 0u, 0u);
}

// The chance that next-event estimation picks the ambient light over the scene's lights at a vertex. At a
// path's last vertex, which no BSDF-sampled ray follows, it is in proportion to power (f.ambient.w). Before
// it, only where the scene has no lights (f.ambient.w is 1 then): with lights, the ambient light is found by
// BSDF sampling alone, which has little variance on surfaces open to the sky, while taking next-event
// samples from a sun for it doubled the noise of the studio-lit shared scenes (docs/sampling.md).
float ambientChance(FrameConstants f, SceneDesc scene, bool lastVertex) {
    return lastVertex || !sceneHasLights(scene) ? f.ambient.w : 0.0;
}

// Next-event estimation: the ambient light with chance ambientChance(), else one of the scene's lights picked
// in proportion to power; its contribution MIS-weighted against BSDF sampling (weight 1 for delta lights, and
// where the path ends here so no BSDF ray will follow), as a shadow request.
// In a medium (m.kind MATERIAL_VOLUME) the BSDF is the phase function (times the albedo) and the shadow ray
// starts at the collision itself.
void sampleOneLight(FrameConstants f, SceneDesc scene, SurfaceMaterial m, Lobes lobes, vec3 position, vec3 geometricNormal,
                    vec3 n, vec3 wo, vec3 throughput, uint slot, vec4 u, bool lastVertex) {
    bool medium = hasFeature(FEATURE_VOLUMES) && m.kind == MATERIAL_VOLUME;
    float chance = ambientChance(f, scene, lastVertex);
    LightSample ls;
    float misPdf;  // the light strategy's pdf in the MIS weight, selection included
    if (u.x < chance) {
        ls.direction = medium ? sampleUniformSphere(u.yz) : toWorld(sampleCosineHemisphere(u.yz), n);
        ls.pdf = ambientPdf(n, ls.direction, medium);
        if (!(ls.pdf > 0.0)) return;
        ls.distance = INFINITY;
        ls.incident = f.ambient.rgb / (chance * ls.pdf);
        misPdf = chance * ls.pdf;
    } else {
        if (!sceneHasLights(scene)) return;
        float lightsChance = 1.0 - chance;
        LightRecord light = LightsRef(scene.lights).lights[pickLight(scene, min((u.x - chance) / lightsChance, 1.0))];
        float selection = lightsChance * light.emission.w;
        if (!(selection > 0.0) || !sampleLight(scene, light, position, u.yz, ls)) return;
        ls.incident /= selection;
        misPdf = selection * ls.pdf;
    }
    bool delta = ls.pdf == 0.0;
    if (!delta && f.lightSampling == LIGHT_SAMPLING_BSDF_ONLY && !lastVertex) return;
    float side = dot(ls.direction, geometricNormal);
    if (!medium && (side == 0.0 || (side < 0.0 && m.transmission == 0.0))) return;
    float bsdfPdf = medium ? phaseHG(dot(-wo, ls.direction), f.phaseAnisotropy) : 0.0;
    vec3 fCos = medium ? m.baseColor * bsdfPdf : evalBsdf(m, lobes, n, wo, ls.direction, bsdfPdf);
    float w = delta || lastVertex || f.lightSampling == LIGHT_SAMPLING_LIGHTS_ONLY ? 1.0 : misWeight(misPdf, bsdfPdf);
    vec3 contribution = clamped(f, throughput * fCos * ls.incident * w);
    // Stop just short of the light, so geometry at the light itself does not shadow it.
    float tmax = isinf(ls.distance) ? INFINITY : ls.distance * (1.0 - 1e-4);
    vec3 origin = medium ? position : offsetRayOrigin(position, side > 0.0 ? geometricNormal : -geometricNormal, scene.originUnit);
    if (maxComponent(contribution) > 0.0) appendShadow(Ray(vec4(origin, 0.0), vec4(ls.direction, tmax)), contribution, slot);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= stageCount()) return;
    FrameConstants f = FrameRef(params.frame).frame;
    SceneDesc scene = SceneRef(params.scene).desc;
    Ray ray = RaysRef(params.rays).rays[i];
    SurfaceRecord r = SurfacesRef(params.surfaces).records[i];
    PathState path = PathsRef(params.paths).paths[i];
    PixelSample ps = pixelSample(f, path.slot);
    Vec4sRef radiance = Vec4sRef(f.sampleRadiance);
    bool camera = (path.flags & PATH_FLAG_CAMERA) != 0u;
    uint passThroughs = (path.flags >> PATH_PASS_THROUGH_SHIFT) & 0xFFu;
    vec3 direction = normalize(ray.direction.xyz);
    bool found = r.status == HIT_FOUND;  // else a miss, or a flagged traversal treated as one
    float hitT = found ? r.position.w : INFINITY;

    if ((r.status & ~0xFFu) != 0u) atomicAdd(CountersRef(f.counters).counters.flagged, 1u);
    if (!camera)
        radiance.values[path.slot].rgb += clamped(f, path.throughput.rgb * testedLightsRadiance(scene, ray.origin.xyz, direction,
                                                   hitT, path.throughput.w, path.bsdfPdf, f.lightSampling));
    if (!found) {
        if (camera) {
            radiance.values[path.slot] += vec4(path.throughput.rgb * f.background.rgb, f.background.a);
        } else {  // the ambient light, weighted against its next-event estimation at the vertex before
            float lightPdf = path.ambientPdf;
            float w = !(lightPdf > 0.0) || !(path.bsdfPdf > 0.0) ? 1.0  // next-event estimation cannot reach it
                    : f.lightSampling == LIGHT_SAMPLING_LIGHTS_ONLY ? 0.0
                    : f.lightSampling == LIGHT_SAMPLING_BSDF_ONLY ? 1.0
                    : misWeight(path.bsdfPdf, lightPdf);
            radiance.values[path.slot].rgb += clamped(f, path.throughput.rgb * f.ambient.rgb * w);
        }
        return;
    }
    if (camera && passThroughs == 0u && f.depth != 0ul && ps.latest) FloatsRef(f.depth).values[ps.pixel] = r.position.w;

    vec3 position = r.position.xyz;
    vec3 geometricNormal = r.geometricNormal.xyz;
    vec3 wo = -direction;
    vec4 uLight = random4(ps.pixel, ps.index, params.bounce, RNG_LIGHT, f.seed);
    if ((path.flags >> PATH_DEPTH_SHIFT) == 0u)
        uLight.yz = stratified2D(ps.pixel, ps.stratified, RNG_FIRST_LIGHT, f.seed);

    // Transparency: continue straight on, unchanged, with probability 1 - opacity.
    if (uLight.w >= r.geometricNormal.w) {
        if (passThroughs >= PATH_MAX_PASS_THROUGHS) return;
        path.flags += 1u << PATH_PASS_THROUGH_SHIFT;
        path.throughput.w += hitT;
        // A camera ray keeps what is left of its reach (the camera's far plane); the direction is unchanged.
        float reach = camera ? ray.direction.w - hitT : INFINITY;
        appendPath(Ray(vec4(offsetRayOrigin(position, -geometricNormal, scene.originUnit), 0.0), vec4(ray.direction.xyz, reach)), path);
        return;
    }
    if (camera) radiance.values[path.slot].a = 1.0;
    float emissionWeight = 1.0;
    if (!camera && r.shadingNormal.w > 0.0) {  // a light that next-event estimation samples too
        float lightPdf = surfaceLightPdf(scene, r.shadingNormal.w, path.throughput.w + hitT, dot(geometricNormal, wo));
        emissionWeight = f.lightSampling == LIGHT_SAMPLING_LIGHTS_ONLY ? 0.0
                       : f.lightSampling == LIGHT_SAMPLING_BSDF_ONLY || !(path.bsdfPdf > 0.0) ? 1.0
                       : misWeight(path.bsdfPdf, lightPdf);
    }
    radiance.values[path.slot].rgb += clamped(f, path.throughput.rgb * r.emission.rgb * emissionWeight);

    SurfaceMaterial m = surfaceMaterial(r, scene);
    vec3 n = r.shadingNormal.xyz;
    if (dot(n, wo) <= 0.0) n = geometricNormal;  // interpolated normals can face away from the viewer
    if (f.shading == SHADING_EYE_LIGHT) {  // the quick look ends at the first interaction (see path.h)
        float facing = hasFeature(FEATURE_VOLUMES) && m.kind == MATERIAL_VOLUME ? 1.0 : abs(dot(n, wo));
        radiance.values[path.slot].rgb += clamped(f, path.throughput.rgb * m.baseColor * f.ambient.rgb *
                                                          mix(1.0, facing, f.eyeLightBlendRatio));
        return;
    }
    uint depth = (path.flags >> PATH_DEPTH_SHIFT) + 1u;
    Lobes lobes = lobesOf(m, n, wo);
    sampleOneLight(f, scene, m, lobes, position, geometricNormal, n, wo, path.throughput.rgb, path.slot, uLight,
                   depth >= f.maxPathLength);

    if (depth >= f.maxPathLength) return;
    vec4 uBsdf = random4(ps.pixel, ps.index, params.bounce, RNG_BSDF, f.seed);
    if (depth == 1u) uBsdf.yz = stratified2D(ps.pixel, ps.stratified, RNG_FIRST_BSDF, f.seed);
    vec3 wi;
    vec3 weight;
    float pdf;
    bool medium = hasFeature(FEATURE_VOLUMES) && m.kind == MATERIAL_VOLUME;
    if (medium) {  // the phase function sampled exactly: phase / pdf = 1, so the weight is the albedo
        wi = samplePhase(-wo, f.phaseAnisotropy, uBsdf.yz);
        weight = m.baseColor;
        pdf = phaseHG(dot(-wo, wi), f.phaseAnisotropy);
    } else if (!sampleBsdf(m, lobes, n, wo, uBsdf.xyz, wi, weight, pdf)) {
        return;
    }
    float side = dot(wi, geometricNormal);
    // Below the true surface without transmission, or a refraction that the true surface reflects: the
    // path ends.
    if (!medium && (side == 0.0 || (side < 0.0) != (dot(wi, n) < 0.0))) return;
    vec3 throughput = path.throughput.rgb * weight;
    if (depth >= ROULETTE_FROM_DEPTH) {
        float survive = min(maxComponent(throughput), 0.95);
        if (uBsdf.w >= survive) return;
        throughput /= survive;
    }
    if (!(maxComponent(throughput) > 0.0)) return;
    vec3 origin = medium ? position : offsetRayOrigin(position, side > 0.0 ? geometricNormal : -geometricNormal, scene.originUnit);
    uint flags = (path.flags & ~PATH_FLAG_CAMERA & ((1u << PATH_DEPTH_SHIFT) - 1u)) | (depth << PATH_DEPTH_SHIFT);
    appendPath(Ray(vec4(origin, 0.0), vec4(wi, INFINITY)),
               PathState(vec4(throughput, 0.0), path.slot, flags, pdf,
                         ambientChance(f, scene, false) * ambientPdf(n, wi, medium)));
}
