// Lights for next-event estimation and for BSDF-sampled rays, and the weights that combine the two
// (multiple importance sampling, power heuristic). Delta lights (point, spot, and directional without an
// angular diameter) are reached by next-event estimation only. Area lights: quad, ring, hdri and the disc
// of a directional light with an angular diameter (a sun) are not geometry, so a BSDF-sampled ray tests
// them itself (testedLightsRadiance); emissive triangles are geometry, found by the trace, and their
// light pdf comes from the density pt_surface stores in the SurfaceRecord (surfaceLightPdf). A light is
// picked with the probability stored in its record (proportional to power). Needs texture.glsl.
// The code of each light kind is kept only where the kernel's FeatureSet may hold such lights (a smaller
// pt_shade builds sooner; lavapipe's run time did not change measurably, as it skips a branch no lane takes).
#ifndef RIPPLE_LIGHTS_GLSL
#define RIPPLE_LIGHTS_GLSL
#include "features.glsl"

// Whether this kernel keeps the code of lights of `kind` (LIGHT_*): a specialization constant expression.
#define keepsLightKind(kind) hasFeature(1u << (FEATURE_LIGHT_SHIFT + (kind)))

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightsRef { LightRecord lights[]; };

struct LightSample {
    vec3 direction;   // unit, from the shading point toward the light
    float distance;   // to the sampled point on the light; +inf for directional and hdri lights
    vec3 incident;    // what multiplies f * cos: radiance (or intensity / d^2) divided by the point's pdf
    float pdf;        // solid-angle pdf of the direction (not counting the light's selection); 0: a delta light
};

// w of the strategy with pdf a against one with pdf b, power heuristic; safe for huge or infinite pdfs.
float misWeight(float a, float b) {
    if (!(a > 0.0)) return 0.0;
    if (a >= b) { float r = b / a; return 1.0 / (1.0 + r * r); }
    float r = a / b;
    return r * r / (1.0 + r * r);
}

// Whether next-event estimation has any of the scene's lights to pick (ambientLightChance on the host,
// core/scene/LightTable.h, counts them the same way: a power total above 0).
bool sceneHasLights(SceneDesc scene) { return scene.lightCount > 0u && scene.lightPowerTotal > 0.0; }

// Index of the light whose cdf interval holds u (binary search over the cdfs in position.w).
uint pickLight(SceneDesc scene, float u) {
    LightsRef lights = LightsRef(scene.lights);
    uint lo = 0u, hi = scene.lightCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (u < lights.lights[mid].position.w) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

// Full light within the inner cone, none outside the outer, smooth between (cosines in edge1.xy).
float spotProfile(LightRecord light, float cosAxis) {
    return smoothstep(light.edge1.x, max(light.edge1.y, light.edge1.x + 1e-6), cosAxis);
}

// --- the equirectangular environment (hdri) ---

vec3 environmentSide(LightRecord light) { return cross(light.edge2.xyz, light.direction.xyz); }

// Index of the first cdf entry (of n, at word `first`) above u.
uint searchCdf(uint64_t texels, uint first, uint n, float u) {
    UintsRef words = UintsRef(texels);
    uint lo = 0u, hi = n - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (u < uintBitsToFloat(words.values[first + mid])) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

float cdfStep(uint64_t texels, uint first, uint i) {
    UintsRef words = UintsRef(texels);
    float below = i > 0u ? uintBitsToFloat(words.values[first + i - 1u]) : 0.0;
    return uintBitsToFloat(words.values[first + i]) - below;
}

// Radiance of the environment seen along d, and the solid-angle pdf of sampling d.
vec3 environmentRadiance(SceneDesc scene, LightRecord light, vec3 d, out float pdf) {
    TextureRecord tex = TexturesRef(scene.textures).textures[light.texture];
    float x = dot(d, light.direction.xyz), y = dot(d, environmentSide(light)), z = dot(d, light.edge2.xyz);
    float u = 0.5 + atan(y, x) / (2.0 * PI);
    float v = acos(clamp(z, -1.0, 1.0)) / PI;
    uint col = min(uint(u * float(tex.width)), tex.width - 1u);
    uint row = min(uint(v * float(tex.height)), tex.height - 1u);
    float sinTheta = sqrt(max(0.0, 1.0 - z * z));
    float probability = cdfStep(scene.texels, light.distribution, row) *
                        cdfStep(scene.texels, light.distribution + tex.height + row * tex.width, col);
    pdf = sinTheta > 0.0 ? probability * float(tex.width * tex.height) / (2.0 * PI * PI * sinTheta) : 0.0;
    return fetchTexel(tex, scene.texels, int(col), int(row)).rgb * light.emission.rgb;
}

bool sampleEnvironment(SceneDesc scene, LightRecord light, vec2 u, out LightSample s) {
    TextureRecord tex = TexturesRef(scene.textures).textures[light.texture];
    uint row = searchCdf(scene.texels, light.distribution, tex.height, u.x);
    uint colFirst = light.distribution + tex.height + row * tex.width;
    uint col = searchCdf(scene.texels, colFirst, tex.width, u.y);
    // A point within the texel, reusing what is left of u inside the chosen cdf intervals.
    float rowLow = row > 0u ? uintBitsToFloat(UintsRef(scene.texels).values[light.distribution + row - 1u]) : 0.0;
    float colLow = col > 0u ? uintBitsToFloat(UintsRef(scene.texels).values[colFirst + col - 1u]) : 0.0;
    vec2 within = clamp(vec2((u.y - colLow) / max(cdfStep(scene.texels, colFirst, col), 1e-30),
                             (u.x - rowLow) / max(cdfStep(scene.texels, light.distribution, row), 1e-30)), 0.0, 0.999999);
    float phi = ((float(col) + within.x) / float(tex.width) - 0.5) * 2.0 * PI;
    float theta = (float(row) + within.y) / float(tex.height) * PI;
    s.direction = sin(theta) * (cos(phi) * light.direction.xyz + sin(phi) * environmentSide(light)) + cos(theta) * light.edge2.xyz;
    s.distance = INFINITY;
    vec3 radiance = environmentRadiance(scene, light, s.direction, s.pdf);
    if (!(s.pdf > 0.0)) return false;
    s.incident = radiance / s.pdf;
    return true;
}

// --- the disc of a directional light (a sun) ---
// Uniform radiance over a cone of half angle a about -direction, 1 - cos a = c (edge1.x): the irradiance on
// a surface facing it is radiance * pi sin^2 a, so radiance = irradiance / (pi c (2 - c)); directions are
// sampled uniformly in the cone's solid angle 2 pi c.

float sunSolidAngle(LightRecord light) { return 2.0 * PI * light.edge1.x; }

vec3 sunRadiance(LightRecord light) {
    float c = light.edge1.x;
    return light.emission.rgb / (PI * c * (2.0 - c));
}

vec3 sampleSunDisc(LightRecord light, vec2 u) {
    float oneMinusCos = u.x * light.edge1.x;
    float cosTheta = 1.0 - oneMinusCos;
    float sinTheta = sqrt(max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
    float phi = 2.0 * PI * u.y;
    vec3 axis = -light.direction.xyz;
    vec3 t, b;
    orthonormalFrame(axis, t, b);
    return normalize(sinTheta * (cos(phi) * t + sin(phi) * b) + cosTheta * axis);
}

// --- sampling a light from a point ---

// False when the light sends nothing toward p (behind a one-sided emitter, outside a spot, p on the light).
bool sampleLight(SceneDesc scene, LightRecord light, vec3 p, vec2 u, out LightSample s) {
    s.direction = vec3(0.0, 0.0, 1.0);
    s.distance = 0.0;
    s.incident = vec3(0.0);
    s.pdf = 0.0;
    if (keepsLightKind(LIGHT_DIRECTIONAL) && light.kind == LIGHT_DIRECTIONAL) {
        s.distance = INFINITY;
        if (light.edge1.x > 0.0) {
            s.direction = sampleSunDisc(light, u);
            s.pdf = 1.0 / sunSolidAngle(light);
            s.incident = sunRadiance(light) * sunSolidAngle(light);
        } else {
            s.direction = -light.direction.xyz;
            s.incident = light.emission.rgb;
        }
        return true;
    }
    if (keepsLightKind(LIGHT_HDRI) && light.kind == LIGHT_HDRI) return sampleEnvironment(scene, light, u, s);
    if (!keepsLightKind(LIGHT_QUAD) && !keepsLightKind(LIGHT_TRIANGLE) && !keepsLightKind(LIGHT_RING) &&
        !keepsLightKind(LIGHT_POINT) && !keepsLightKind(LIGHT_SPOT))
        return false;
    vec3 target = light.position.xyz;
    if (keepsLightKind(LIGHT_QUAD) && light.kind == LIGHT_QUAD) {
        target += u.x * light.edge1.xyz + u.y * light.edge2.xyz;
    } else if (keepsLightKind(LIGHT_TRIANGLE) && light.kind == LIGHT_TRIANGLE) {
        float su = sqrt(u.x);
        target += su * (1.0 - u.y) * light.edge1.xyz + su * u.y * light.edge2.xyz;
    } else if (keepsLightKind(LIGHT_RING) && light.kind == LIGHT_RING) {
        float inner = light.edge2.w, outer = light.edge1.z;
        float r = sqrt(mix(inner * inner, outer * outer, u.x));
        float phi = 2.0 * PI * u.y;
        vec3 t, b;
        orthonormalFrame(light.direction.xyz, t, b);
        target += r * (cos(phi) * t + sin(phi) * b);
    }
    vec3 toLight = target - p;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0)) return false;
    s.distance = sqrt(d2);
    s.direction = toLight / s.distance;
    if ((keepsLightKind(LIGHT_POINT) || keepsLightKind(LIGHT_SPOT)) && (light.kind == LIGHT_POINT || light.kind == LIGHT_SPOT)) {
        float profile = keepsLightKind(LIGHT_SPOT) && light.kind == LIGHT_SPOT
                            ? spotProfile(light, dot(light.direction.xyz, -s.direction)) : 1.0;
        s.incident = light.emission.rgb * (profile / d2);
        return profile > 0.0;
    }
    // Area lights: radiance * cos at the light / d^2 / (1 / area).
    float cosLight = -dot(light.direction.xyz, s.direction);
    if (light.twoSided != 0u) cosLight = abs(cosLight);
    if (cosLight <= 0.0) return false;
    float radiance = keepsLightKind(LIGHT_RING) && light.kind == LIGHT_RING ? spotProfile(light, cosLight) : 1.0;
    s.pdf = d2 / (cosLight * light.edge1.w);  // edge1.w: area
    s.incident = light.emission.rgb * (radiance / s.pdf);
    return radiance > 0.0;
}

// --- what BSDF-sampled rays find ---

// Solid-angle pdf with which next-event estimation picks a point of an emissive triangle, from the density
// pt_surface stored (2 pi luminance(emission); the light's power share divided by its area, times
// lightPowerTotal), the distance to it and the cosine there.
float surfaceLightPdf(SceneDesc scene, float density, float distance, float cosLight) {
    if (!(density > 0.0) || !(scene.lightPowerTotal > 0.0)) return 0.0;
    return density / scene.lightPowerTotal * distance * distance / max(abs(cosLight), 1e-12);
}

// Emission that a BSDF-sampled ray (from o along unit d, up to tmax; `before` is the distance from the
// scattering point to o when the ray passed through transparent surfaces) collects from the quad, ring,
// hdri and sun-disc lights, each weighted against next-event estimation with `bsdfPdf`.
vec3 testedLightsRadiance(SceneDesc scene, vec3 o, vec3 d, float tmax, float before, float bsdfPdf, uint strategy) {
    if (strategy == LIGHT_SAMPLING_LIGHTS_ONLY) return vec3(0.0);
    vec3 sum = vec3(0.0);
    LightsRef lights = LightsRef(scene.lights);
    for (uint i = 0u; i < scene.testedLightCount; ++i) {
        LightRecord light = lights.lights[i];
        vec3 radiance;
        float pdf;  // solid angle, of next-event estimation
        if (keepsLightKind(LIGHT_HDRI) && light.kind == LIGHT_HDRI) {
            if (!isinf(tmax)) continue;
            radiance = environmentRadiance(scene, light, d, pdf);
        } else if (keepsLightKind(LIGHT_DIRECTIONAL) && light.kind == LIGHT_DIRECTIONAL) {
            if (!isinf(tmax) || 1.0 + dot(d, light.direction.xyz) > light.edge1.x) continue;
            radiance = sunRadiance(light);
            pdf = 1.0 / sunSolidAngle(light);
        } else if (keepsLightKind(LIGHT_QUAD) || keepsLightKind(LIGHT_RING)) {
            vec3 n = light.direction.xyz;
            float cosLight = -dot(n, d);
            if (cosLight == 0.0 || (cosLight < 0.0 && light.twoSided == 0u)) continue;
            float t = dot(light.position.xyz - o, n) / dot(d, n);
            if (!(t > 0.0 && t < tmax)) continue;
            vec3 q = o + t * d - light.position.xyz;
            if (keepsLightKind(LIGHT_QUAD) && light.kind == LIGHT_QUAD) {
                // Coordinates along the (not necessarily orthogonal) edges.
                vec3 e1 = light.edge1.xyz, e2 = light.edge2.xyz;
                float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
                float det = a11 * a22 - a12 * a12;
                float b1 = dot(q, e1), b2 = dot(q, e2);
                float s1 = (a22 * b1 - a12 * b2) / det, s2 = (a11 * b2 - a12 * b1) / det;
                if (s1 < 0.0 || s1 > 1.0 || s2 < 0.0 || s2 > 1.0) continue;
                radiance = light.emission.rgb;
            } else if (keepsLightKind(LIGHT_RING)) {
                float r2 = dot(q, q);
                if (r2 > light.edge1.z * light.edge1.z || r2 < light.edge2.w * light.edge2.w) continue;
                radiance = light.emission.rgb * spotProfile(light, cosLight);
            } else {
                continue;
            }
            float distance = before + t;
            pdf = distance * distance / (abs(cosLight) * light.edge1.w);
        } else {
            continue;
        }
        float w = strategy == LIGHT_SAMPLING_BSDF_ONLY || !(bsdfPdf > 0.0) ? 1.0 : misWeight(bsdfPdf, light.emission.w * pdf);
        sum += radiance * w;
    }
    return sum;
}

// --- the ambient light: a uniform environment of radiance FrameConstants.ambient.rgb ---

// The solid-angle pdf with which next-event estimation samples the ambient light's direction wi, once it has
// picked the ambient light over the scene's lights (ambientChance in pt_shade.comp): proportional to the
// cosine to the shading normal n, or uniform over the sphere in a medium.
float ambientPdf(vec3 n, vec3 wi, bool medium) { return medium ? 0.25 / PI : max(dot(wi, n), 0.0) / PI; }

#endif
