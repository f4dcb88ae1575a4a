#version 460
// Stage 3 of a bounce (after the closest-hit trace), run by the rank that owns each hit: the surface at
// the hit (position, normals, attributes) and its material evaluated there (vertex color, textures for
// base color, opacity, metallic, roughness, emission and the normal map, alpha mode) are packed into a
// SurfaceRecord, so the path's home rank can shade it without the scene.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "bsdf.glsl"
#include "surface.glsl"
#include "texture.glsl"
#include "sampler.glsl"
#include "ids.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialsRef { MaterialRecord materials[]; };

// The shading normal bent by a tangent-space normal map value m (rgb in [0,1] -> [-1,1]) around ns.
vec3 normalMapped(SurfacePoint s, vec3 m) {
    vec3 t = s.tangent - dot(s.tangent, s.shadingNormal) * s.shadingNormal;
    if (!(dot(t, t) > 0.0)) return s.shadingNormal;
    t = normalize(t);
    vec3 b = s.tangentSign * cross(s.shadingNormal, t);
    m = m * 2.0 - 1.0;
    // A back-face hit sees the surface flipped: keep the map's bump on the viewer's side.
    if (!s.frontFace) b = -b;
    vec3 n = safeNormalize(m.x * t + m.y * b + m.z * s.shadingNormal, s.shadingNormal);
    return dot(n, s.geometricNormal) > 0.0 ? n : s.shadingNormal;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= stageCount()) return;
    Hit hit = HitsRef(params.hits).hits[i];
    SurfaceRecord r;
    r.status = hit.status;
    r.position = vec4(0.0, 0.0, 0.0, hit.t);
    r.geometricNormal = vec4(0.0);
    r.shadingNormal = vec4(0.0);
    r.baseColor = vec4(0.0);
    r.emission = vec4(0.0);
    r.layers = vec4(0.0, 0.0, MIN_GGX_ALPHA, 1.0);
    r.materialKind = MATERIAL_MATTE;
    r.f0 = 0.0;
    r.pad0 = 0u;
    if (hit.status == HIT_FOUND) {
        SceneDesc scene = SceneRef(params.scene).desc;
        Ray ray = RaysRef(params.rays).rays[i];
        SurfacePoint s = surfaceAt(scene, ray, hit);
        MaterialRecord rec = MaterialsRef(scene.materials).materials[s.material];
        vec3 baseColor = rec.baseColorOpacity.rgb;
        float opacity = rec.baseColorOpacity.a;
        if ((rec.flags & MATERIAL_FLAG_VERTEX_COLOR) != 0u && s.hasColor) {
            baseColor = s.color.rgb;
            opacity *= s.color.a;
        }
        vec3 emission = rec.emissiveIor.rgb;
        float metallic = rec.metallic;
        float roughness = rec.roughness;
        vec3 shadingNormal = s.shadingNormal;
        // The texture code, the largest part of this kernel, only when the scene has textures; and then a
        // loop over the material's six texture slots, so that it is compiled once rather than six times.
        if (hasFeature(FEATURE_TEXTURES)) {
            for (uint slot = 0u; slot < 6u; ++slot) {
                int texture = slot == 0u ? rec.baseColorTexture : slot == 1u ? rec.opacityTexture
                            : slot == 2u ? rec.emissiveTexture : slot == 3u ? rec.metallicTexture
                            : slot == 4u ? rec.roughnessTexture : rec.normalTexture;
                if (texture == NO_TEXTURE) continue;
                // Float parameters take the texture's first component (ANARI's rule for samplers).
                vec4 value = sampleTexture(scene, texture, s);
                if (slot == 0u) {
                    baseColor *= value.rgb;
                    opacity *= value.a;
                } else if (slot == 1u) {
                    opacity *= value.x;
                } else if (slot == 2u) {
                    emission *= value.rgb;
                } else if (slot == 3u) {
                    metallic *= value.x;
                } else if (slot == 4u) {
                    roughness *= value.x;
                } else {
                    shadingNormal = normalMapped(s, value.xyz);
                }
            }
        }
        if (rec.alphaMode == ALPHA_OPAQUE) opacity = 1.0;
        else if (rec.alphaMode == ALPHA_MASK) opacity = opacity >= rec.alphaCutoff ? 1.0 : 0.0;
        metallic = clamp(metallic, 0.0, 1.0);
        roughness = clamp(roughness, 0.0, 1.0);
        float ior = rec.emissiveIor.w;
        float f = (ior - 1.0) / (ior + 1.0);
        r.position.xyz = s.position;
        r.geometricNormal = vec4(s.geometricNormal, clamp(opacity, 0.0, 1.0));
        // A light triangle: 2 pi luminance(emission), the density LightTable's selection power implies.
        uint geometry = InstanceShadingRef(scene.instanceShading).instances[hit.instanceId].geometry;
        bool light = (rec.flags & MATERIAL_FLAG_LIGHT) != 0u &&
                     GeometriesRef(scene.geometries).geometries[geometry].kind == GEOMETRY_TRIANGLES;
        r.shadingNormal = vec4(shadingNormal, light ? 2.0 * PI * luminance(emission) : 0.0);
        r.baseColor = vec4(max(baseColor, vec3(0.0)), metallic);
        r.emission = vec4(max(emission, vec3(0.0)), max(roughness * roughness, MIN_GGX_ALPHA));
        r.layers = vec4(rec.transmission, rec.clearcoat, max(rec.clearcoatRoughness * rec.clearcoatRoughness, MIN_GGX_ALPHA),
                        s.frontFace ? ior : 1.0 / ior);
        r.materialKind = rec.kind;
        r.f0 = min(f * f * rec.specular, 1.0);
    }
    writeSurfaceIds(r, hit);
    SurfacesRef(params.surfaces).records[i] = r;
}
