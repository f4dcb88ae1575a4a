// The two surface models. Matte: Lambertian, sampled by the cosine. physicallyBased: the glTF
// metallic-roughness model (glTF 2.0 spec, appendix B): a GGX microfacet specular lobe (Walter et al.
// 2007, alpha = roughness^2 as Karis 2013, height-correlated Smith masking) whose Schlick Fresnel goes
// from the dielectric F0 of the ior to the base color with metallic, over a Lambertian lobe weighted by
// (1 - metallic)(1 - F). The specular lobe is sampled by its visible normals (Heitz, "Sampling the GGX
// Distribution of Visible Normals", JCGT 2018); the two lobes are picked stochastically and combined in
// one mixture pdf. All directions are unit vectors pointing away from the surface; n is the shading normal.
#ifndef RIPPLE_BSDF_GLSL
#define RIPPLE_BSDF_GLSL

#include "sampling.glsl"

struct SurfaceMaterial {
    uint kind;         // MATERIAL_*
    vec3 baseColor;
    float metallic;
    float alpha;       // GGX roughness: roughness^2, kept above a floor so the lobe stays a function
    float f0;          // dielectric reflectance at normal incidence, from the ior
};

const float MIN_GGX_ALPHA = 1e-3;

float ggxD(float nh, float a2) {
    float d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

// Smith Lambda for GGX, of a direction with cosine c to the normal.
float ggxLambda(float c, float a2) {
    float c2 = c * c;
    return 0.5 * (-1.0 + sqrt(1.0 + a2 * max(0.0, 1.0 - c2) / max(c2, 1e-12)));
}

vec3 schlick(vec3 f0, float c) {
    float m = clamp(1.0 - c, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// Chance of sampling the specular lobe: its Fresnel weight at normal incidence of wo against the diffuse one.
float specularChance(SurfaceMaterial m, float nv) {
    vec3 f = schlick(mix(vec3(m.f0), m.baseColor, m.metallic), nv);
    float spec = luminance(f);
    float diffuse = (1.0 - m.metallic) * (1.0 - luminance(schlick(vec3(m.f0), nv))) * luminance(m.baseColor);
    return spec + diffuse > 0.0 ? clamp(spec / (spec + diffuse), 0.05, 1.0) : 1.0;
}

// f(wo, wi) * cos(n, wi), and the pdf with which sampleBsdf picks wi.
vec3 evalBsdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    float nl = dot(n, wi);
    float nv = dot(n, wo);
    if (nl <= 0.0 || nv <= 0.0) return vec3(0.0);
    if (m.kind == MATERIAL_MATTE) {
        pdf = nl / PI;
        return m.baseColor * (nl / PI);
    }
    vec3 h = normalize(wo + wi);
    float nh = max(dot(n, h), 0.0);
    float vh = max(dot(wo, h), 0.0);
    float a2 = m.alpha * m.alpha;
    float D = ggxD(nh, a2);
    float lambdaV = ggxLambda(nv, a2);
    float G2 = 1.0 / (1.0 + lambdaV + ggxLambda(nl, a2));
    float G1 = 1.0 / (1.0 + lambdaV);
    vec3 F = schlick(mix(vec3(m.f0), m.baseColor, m.metallic), vh);
    float dielectricF = schlick(vec3(m.f0), vh).x;
    vec3 specular = F * (D * G2 / (4.0 * nv));                      // times nl / nl
    vec3 diffuse = (1.0 - m.metallic) * (1.0 - dielectricF) * m.baseColor * (nl / PI);
    float pSpec = specularChance(m, nv);
    pdf = pSpec * (G1 * D / (4.0 * nv)) + (1.0 - pSpec) * (nl / PI);
    return specular + diffuse;
}

// Samples wi; weight = f * cos / pdf. False when the sample carries nothing (below the surface).
bool sampleBsdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 u, out vec3 wi, out vec3 weight) {
    weight = vec3(0.0);
    if (m.kind == MATERIAL_MATTE) {
        wi = toWorld(sampleCosineHemisphere(u.yz), n);
        weight = m.baseColor;  // (base / pi) * cos / (cos / pi)
        return dot(n, wi) > 0.0;
    }
    float nv = dot(n, wo);
    if (u.x < specularChance(m, nv)) {
        vec3 v = toLocal(wo, n);
        // Visible normal: stretch the view to the hemisphere configuration, sample a disk projected on it,
        // unstretch.
        vec3 vh = normalize(vec3(m.alpha * v.x, m.alpha * v.y, v.z));
        float lensq = vh.x * vh.x + vh.y * vh.y;
        vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
        vec3 t2 = cross(vh, t1);
        float r = sqrt(u.y);
        float phi = 2.0 * PI * u.z;
        float p1 = r * cos(phi);
        float p2 = r * sin(phi);
        float s = 0.5 * (1.0 + vh.z);
        p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
        vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
        vec3 microNormal = normalize(vec3(m.alpha * nh.x, m.alpha * nh.y, max(0.0, nh.z)));
        wi = toWorld(reflect(-v, microNormal), n);
    } else {
        wi = toWorld(sampleCosineHemisphere(u.yz), n);
    }
    float pdf;
    vec3 fCos = evalBsdf(m, n, wo, wi, pdf);
    if (!(pdf > 0.0)) return false;
    weight = fCos / pdf;
    return true;
}

#endif
