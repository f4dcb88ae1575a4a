// The surface models. Matte: Lambertian. physicallyBased: the glTF metallic-roughness model with its
// clearcoat, specular and transmission extensions, as four lobes:
//   clear coat  GGX, F0 0.04, over everything below it;
//   specular    GGX whose Schlick F0 goes from the dielectric F0 (ior, times "specular") to the base color
//               with metallic; Walter et al. 2007, alpha = roughness^2, height-correlated Smith masking;
//   diffuse     Lambertian, (1 - metallic)(1 - transmission) of what the dielectric specular leaves;
//   transmission  refraction through GGX microfacets (total internal reflection reflects), tinted by the
//               base color, transmission's share of what the dielectric specular leaves.
// Energy: single-scattering GGX loses energy at high roughness; the specular lobes are scaled by
// 1 + F0 (1 - E) / E (Turquin, "Practical multiple scattering compensation for microfacet models", 2019),
// and each layer below passes on exactly 1 - (the directional albedo of the layers above), read from
// tables of E(mu, alpha) integrated at build time (core/scene/BsdfTables.h). So a white material reflects all
// it receives at any roughness (the white furnace test). The transmission lobe's value is its weight
// times its sampling density, so it conserves energy exactly too. GGX lobes are sampled by their visible
// normals (Heitz, JCGT 2018); a lobe is picked in proportion to its albedo and the lobes combined in one
// mixture pdf. A GGX lobe at the roughness floor (alpha MIN_GGX_ALPHA, roughness 0.03 or less) is a
// perfect mirror or refraction instead, as in other production renderers: a delta lobe that only
// sampleBsdf follows (weight its albedo over its chance, pdf 0, so what the ray finds is not MIS-weighted)
// and evalBsdf leaves out. A lobe that narrow cannot be found by light sampling except as a rare, huge
// sample. Directions are unit vectors pointing away from the surface; n is the shading normal, on the
// side of wo.
#ifndef RIPPLE_BSDF_GLSL
#define RIPPLE_BSDF_GLSL

#include "features.glsl"
#include "sampling.glsl"

struct SurfaceMaterial {
    uint kind;           // MATERIAL_*
    vec3 baseColor;
    float metallic;
    float alpha;         // GGX roughness: roughness^2, kept above a floor so the lobe stays a function
    float f0;            // dielectric reflectance at normal incidence, from the ior and the specular factor
    float transmission;
    float clearcoat;
    float clearcoatAlpha;
    float eta;           // refraction: ior on the other side / ior on wo's side (ior when entering)
    uint64_t texels;     // SceneDesc.texels, which hold the energy tables
    uint tableOffset;    // SceneDesc.bsdfTables
};

const float MIN_GGX_ALPHA = 1e-3;
const float CLEARCOAT_F0 = 0.04;   // ior 1.5
// Must match core/scene/BsdfTables.h.
const uint BSDF_TABLE_SIZE = 32u;

// A lobe at the roughness floor is a delta lobe (see above).
bool isSmooth(float alpha) { return alpha <= MIN_GGX_ALPHA; }

// Table `table` (0: E, the albedo of GGX with F = 1; 1: W, the albedo weighted by (1 - v.h)^5) at
// (mu, alpha), bilinear over mu and roughness = sqrt(alpha).
float energyTable(SurfaceMaterial m, uint table, float mu, float alpha) {
    float n = float(BSDF_TABLE_SIZE);
    vec2 x = clamp(vec2(mu * n - 0.5, sqrt(alpha) * (n - 1.0)), vec2(0.0), vec2(n - 1.0));
    vec2 i = min(floor(x), vec2(n - 2.0));
    vec2 f = x - i;
    uint base = m.tableOffset + table * BSDF_TABLE_SIZE * BSDF_TABLE_SIZE + uint(i.y) * BSDF_TABLE_SIZE + uint(i.x);
    UintsRef t = UintsRef(m.texels);
    float v00 = uintBitsToFloat(t.values[base]), v10 = uintBitsToFloat(t.values[base + 1u]);
    float v01 = uintBitsToFloat(t.values[base + BSDF_TABLE_SIZE]), v11 = uintBitsToFloat(t.values[base + BSDF_TABLE_SIZE + 1u]);
    return mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y);
}

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

// Directional albedo of a compensated GGX lobe with Schlick F0, and the compensation factor.
struct LobeEnergy {
    vec3 albedo;
    vec3 compensation;
};

LobeEnergy lobeEnergy(SurfaceMaterial m, vec3 f0, float mu, float alpha) {
    float e = max(energyTable(m, 0u, mu, alpha), 1e-4);
    float w = energyTable(m, 1u, mu, alpha);
    LobeEnergy l;
    l.compensation = 1.0 + f0 * ((1.0 - e) / e);
    l.albedo = (f0 * (e - w) + w) * l.compensation;
    return l;
}

// The lobes' weights at wo: each lobe's share of the albedo, for picking one.
struct Lobes {
    float coat;          // chance of each lobe; they sum to 1 (or all are 0)
    float specular;
    float diffuse;
    float transmission;
    vec3 coatCompensation;
    vec3 specularCompensation;
    vec3 specularF0;
    float coatAlbedo;    // the clear coat's directional albedo times its weight (all a delta coat returns)
    vec3 specularAlbedo; // the specular lobe's times underCoat (all a delta specular lobe returns)
    float underCoat;     // what the clear coat passes on: 1 - its albedo
    float underDielectric; // what the dielectric specular passes on to diffuse and transmission
};

// A physicallyBased material's lobes seen from wo (nv = n.wo): what evalBsdf and sampleBsdf take, computed
// once per shading point (six bilinear table reads, three with a clear coat) and shared by the light
// sample's evaluation and the BSDF sample. A matte material needs none (noLobes).
Lobes lobesAt(SurfaceMaterial m, float nv) {
    Lobes l;
    l.specularF0 = mix(vec3(m.f0), m.baseColor, m.metallic);
    LobeEnergy spec = lobeEnergy(m, l.specularF0, nv, m.alpha);
    LobeEnergy dielectric = lobeEnergy(m, vec3(m.f0), nv, m.alpha);
    l.specularCompensation = spec.compensation;
    l.coatCompensation = vec3(1.0);
    l.coatAlbedo = 0.0;  // m.clearcoat is 0 where the FeatureSet has no clear coat
    if (hasFeature(FEATURE_CLEARCOAT)) {
        LobeEnergy coat = lobeEnergy(m, vec3(CLEARCOAT_F0), nv, m.clearcoatAlpha);
        l.coatCompensation = coat.compensation;
        l.coatAlbedo = m.clearcoat * coat.albedo.x;
    }
    l.underCoat = 1.0 - l.coatAlbedo;
    l.specularAlbedo = l.underCoat * spec.albedo;
    l.underDielectric = clamp(1.0 - dielectric.albedo.x, 0.0, 1.0);
    float base = l.underCoat * (1.0 - m.metallic) * l.underDielectric * luminance(m.baseColor);
    float coatW = l.coatAlbedo;
    float specW = luminance(l.specularAlbedo);
    float diffW = base * (1.0 - m.transmission);
    float transW = base * m.transmission;
    float sum = coatW + specW + diffW + transW;
    float inv = sum > 0.0 ? 1.0 / sum : 0.0;
    l.coat = coatW * inv;
    l.specular = specW * inv;
    l.diffuse = diffW * inv;
    l.transmission = transW * inv;
    return l;
}

// Visible-normal density of h seen from wo (both in the frame of n): G1(wo) max(0, wo.h) D(h) / n.wo.
float visibleNormalPdf(float nv, float nh, float vh, float a2) {
    return vh > 0.0 ? ggxD(nh, a2) * vh / (nv * (1.0 + ggxLambda(nv, a2))) : 0.0;
}

// A rough GGX reflection lobe seen from n.v = nv is sampled by its visible normals or, with this chance, by
// the cosine: a defensive mixture. Near alpha 1 many visible normals mirror wo below the surface (weight 0)
// and G2 / G1 spreads the rest, while f * cos is close to a cosine lobe, the more so the more head-on the
// view; toward grazing views the lobe leans to the mirror direction, where visible normals do better. The
// share was fitted to the relative spread of the weight f * cos / pdf over alpha and nv (F = 1; halved
// variance against the share of alpha alone: docs/sampling.md). Lobes with alpha up to 0.35 (roughness
// 0.6) keep pure visible-normal sampling.
float cosineShare(float alpha, float nv) {
    return clamp((alpha - 0.35) / 0.45, 0.0, 1.0) * clamp(0.3 + 2.2 * nv, 0.0, 1.0);
}

// A GGX reflection lobe: f * cos (without F0 compensation or weight) and its pdf (sampleGgxReflection's).
vec3 ggxReflection(vec3 f0, float alpha, vec3 n, vec3 wo, vec3 wi, out float pdf) {
    float nl = dot(n, wi), nv = dot(n, wo);
    vec3 h = normalize(wo + wi);
    float nh = max(dot(n, h), 0.0), vh = max(dot(wo, h), 0.0);
    float a2 = alpha * alpha;
    float D = ggxD(nh, a2);
    float lambdaV = ggxLambda(nv, a2);
    float G2 = 1.0 / (1.0 + lambdaV + ggxLambda(nl, a2));
    float q = cosineShare(alpha, nv);
    pdf = (1.0 - q) * visibleNormalPdf(nv, nh, vh, a2) / (4.0 * max(vh, 1e-12)) + q * max(nl, 0.0) / PI;
    return schlick(f0, vh) * (D * G2 / (4.0 * nv));  // times nl / nl
}

bool totalInternalReflection(float eta, float vh) { return eta * eta * (1.0 - vh * vh) > 1.0; }

// The transmission lobe's sampling density of wi (refracted through h, or reflected where h totally
// reflects); its f * cos is its weight times this density.
float transmissionPdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
    float nv = dot(n, wo), nl = dot(n, wi);
    float a2 = m.alpha * m.alpha;
    float e = 1.0 / m.eta;  // refract()'s ratio: ior on the incoming side / ior on the outgoing side
    if (nl > 0.0) {
        vec3 h = normalize(wo + wi);
        float vh = dot(wo, h);
        if (!totalInternalReflection(e, vh)) return 0.0;
        return visibleNormalPdf(nv, max(dot(n, h), 0.0), vh, a2) / (4.0 * max(vh, 1e-12));
    }
    vec3 h = e * wo + wi;
    float len = length(h);
    if (!(len > 0.0)) return 0.0;
    h /= len;
    if (dot(h, n) < 0.0) h = -h;
    float vh = dot(wo, h), lh = dot(wi, h);
    if (vh <= 0.0 || lh >= 0.0 || totalInternalReflection(e, vh)) return 0.0;
    float denom = e * vh + lh;
    return visibleNormalPdf(nv, dot(n, h), vh, a2) * abs(lh) / max(denom * denom, 1e-12);
}

Lobes noLobes() {
    Lobes l;
    l.coat = l.specular = l.diffuse = l.transmission = 0.0;
    l.coatCompensation = l.specularCompensation = l.specularF0 = l.specularAlbedo = vec3(0.0);
    l.coatAlbedo = l.underCoat = l.underDielectric = 0.0;
    return l;
}

// The lobes a material has at a shading point (n, wo).
Lobes lobesOf(SurfaceMaterial m, vec3 n, vec3 wo) {
    if (!hasFeature(FEATURE_PHYSICALLY_BASED) || m.kind != MATERIAL_PHYSICALLY_BASED) return noLobes();
    return lobesAt(m, dot(n, wo));
}

// f(wo, wi) * |cos(n, wi)| of the lobes that are not delta lobes, and the pdf with which sampleBsdf picks wi;
// l = lobesOf(m, n, wo).
vec3 evalBsdf(SurfaceMaterial m, Lobes l, vec3 n, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    float nl = dot(n, wi);
    float nv = dot(n, wo);
    if (nv <= 0.0 || nl == 0.0) return vec3(0.0);
    if (!hasFeature(FEATURE_PHYSICALLY_BASED) || m.kind == MATERIAL_MATTE) {
        if (nl < 0.0) return vec3(0.0);
        pdf = nl / PI;
        return m.baseColor * (nl / PI);
    }
    vec3 value = vec3(0.0);
    if (nl > 0.0) {
        float p;
        if (hasFeature(FEATURE_CLEARCOAT) && m.clearcoat > 0.0 && !isSmooth(m.clearcoatAlpha)) {
            value += m.clearcoat * l.coatCompensation * ggxReflection(vec3(CLEARCOAT_F0), m.clearcoatAlpha, n, wo, wi, p);
            pdf += l.coat * p;
        }
        if (!isSmooth(m.alpha)) {
            value += l.underCoat * l.specularCompensation * ggxReflection(l.specularF0, m.alpha, n, wo, wi, p);
            pdf += l.specular * p;
        }
        value += l.underCoat * (1.0 - m.metallic) * (1.0 - m.transmission) * l.underDielectric * m.baseColor * (nl / PI);
        pdf += l.diffuse * (nl / PI);
    }
    if (hasFeature(FEATURE_TRANSMISSION) && m.transmission > 0.0 && !isSmooth(m.alpha)) {
        float p = transmissionPdf(m, n, wo, wi);
        value += l.underCoat * (1.0 - m.metallic) * m.transmission * l.underDielectric * m.baseColor * p;
        pdf += l.transmission * p;
    }
    return value;
}

// A visible normal of GGX (alpha) seen from v (local frame, v.z > 0) for the uniforms u.
vec3 sampleVisibleNormal(vec3 v, float alpha, vec2 u) {
    // Stretch the view to the hemisphere configuration, sample a disk projected on it, unstretch.
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

// wi of a GGX reflection lobe seen from v (local frame), with the density ggxReflection gives: the cosine
// where u.x < cosineShare(alpha, v.z), else the mirror direction about a visible normal. The choice splits
// u.x and rescales it, so that stratified u stay stratified within each branch.
vec3 sampleGgxReflection(vec3 v, float alpha, vec2 u) {
    float q = cosineShare(alpha, v.z);
    if (u.x < q) return sampleCosineHemisphere(vec2(u.x / q, u.y));
    return reflect(-v, sampleVisibleNormal(v, alpha, vec2((u.x - q) / (1.0 - q), u.y)));
}

// Samples wi; weight = f * |cos| / pdf, and its pdf (0 for a delta lobe's direction, whose weight is its
// albedo over its chance). False when the sample carries nothing. l = lobesOf(m, n, wo).
bool sampleBsdf(SurfaceMaterial m, Lobes l, vec3 n, vec3 wo, vec3 u, out vec3 wi, out vec3 weight, out float pdf) {
    weight = vec3(0.0);
    pdf = 0.0;
    if (!hasFeature(FEATURE_PHYSICALLY_BASED) || m.kind == MATERIAL_MATTE) {
        wi = toWorld(sampleCosineHemisphere(u.yz), n);
        weight = m.baseColor;  // (base / pi) * cos / (cos / pi)
        pdf = dot(n, wi) / PI;
        return pdf > 0.0;
    }
    float nv = dot(n, wo);
    if (nv <= 0.0) return false;
    vec3 v = toLocal(wo, n);
    float pick = u.x;
    if (hasFeature(FEATURE_CLEARCOAT) && pick < l.coat) {
        if (isSmooth(m.clearcoatAlpha)) {
            wi = reflect(-wo, n);
            weight = vec3(l.coatAlbedo / l.coat);
            return true;
        }
        wi = toWorld(sampleGgxReflection(v, m.clearcoatAlpha, u.yz), n);
    } else if ((pick -= l.coat) < l.specular) {
        if (isSmooth(m.alpha)) {
            wi = reflect(-wo, n);
            weight = l.specularAlbedo / l.specular;
            return true;
        }
        wi = toWorld(sampleGgxReflection(v, m.alpha, u.yz), n);
    } else if ((pick -= l.specular) < l.diffuse) {
        wi = toWorld(sampleCosineHemisphere(u.yz), n);
    } else if (hasFeature(FEATURE_TRANSMISSION) && l.transmission > 0.0) {
        vec3 h = isSmooth(m.alpha) ? vec3(0.0, 0.0, 1.0) : sampleVisibleNormal(v, m.alpha, u.yz);
        vec3 t = refract(-v, h, 1.0 / m.eta);
        wi = toWorld(dot(t, t) > 0.0 ? t : reflect(-v, h), n);
        if (isSmooth(m.alpha)) {  // the transmission lobe's f * cos is its weight times its density
            weight = l.underCoat * (1.0 - m.metallic) * m.transmission * l.underDielectric * m.baseColor / l.transmission;
            return true;
        }
    } else {
        return false;
    }
    vec3 fCos = evalBsdf(m, l, n, wo, wi, pdf);
    if (!(pdf > 0.0)) return false;
    weight = fCos / pdf;
    return true;
}

#endif
