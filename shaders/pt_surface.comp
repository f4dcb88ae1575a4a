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

// The texture's first output component as a factor (ANARI's rule for float parameters from samplers).
float textureFactor(SceneDesc scene, int texture, SurfacePoint s) {
    return texture == NO_TEXTURE ? 1.0 : sampleTexture(scene, texture, s).x;
}

// The shading normal bent by a tangent-space normal map (rgb in [0,1] -> [-1,1]) around ns.
vec3 normalMapped(SceneDesc scene, int texture, SurfacePoint s) {
    vec3 t = s.tangent - dot(s.tangent, s.shadingNormal) * s.shadingNormal;
    if (texture == NO_TEXTURE || !(dot(t, t) > 0.0)) return s.shadingNormal;
    t = normalize(t);
    vec3 b = s.tangentSign * cross(s.shadingNormal, t);
    vec3 m = sampleTexture(scene, texture, s).xyz * 2.0 - 1.0;
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
        if (rec.baseColorTexture != NO_TEXTURE) {
            vec4 texel = sampleTexture(scene, rec.baseColorTexture, s);
            baseColor *= texel.rgb;
            opacity *= texel.a;
        }
        opacity *= textureFactor(scene, rec.opacityTexture, s);
        if (rec.alphaMode == ALPHA_OPAQUE) opacity = 1.0;
        else if (rec.alphaMode == ALPHA_MASK) opacity = opacity >= rec.alphaCutoff ? 1.0 : 0.0;
        vec3 emission = rec.emissiveIor.rgb;
        if (rec.emissiveTexture != NO_TEXTURE) emission *= sampleTexture(scene, rec.emissiveTexture, s).rgb;
        float metallic = clamp(rec.metallic * textureFactor(scene, rec.metallicTexture, s), 0.0, 1.0);
        float roughness = clamp(rec.roughness * textureFactor(scene, rec.roughnessTexture, s), 0.0, 1.0);
        float ior = rec.emissiveIor.w;
        float f = (ior - 1.0) / (ior + 1.0);
        r.position.xyz = s.position;
        r.geometricNormal = vec4(s.geometricNormal, clamp(opacity, 0.0, 1.0));
        // A light triangle: 2 pi luminance(emission), the density LightTable's selection power implies.
        uint geometry = InstanceShadingRef(scene.instanceShading).instances[hit.instanceId].geometry;
        bool light = (rec.flags & MATERIAL_FLAG_LIGHT) != 0u &&
                     GeometriesRef(scene.geometries).geometries[geometry].kind == GEOMETRY_TRIANGLES;
        r.shadingNormal = vec4(normalMapped(scene, rec.normalTexture, s), light ? 2.0 * PI * luminance(emission) : 0.0);
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
