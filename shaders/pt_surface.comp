#version 460
// Stage 3 of a bounce (after the closest-hit trace), run by the rank that owns each hit: the surface at
// the hit (position, normals, attributes) and its material evaluated there (vertex color, base-color
// texture) are packed into a SurfaceRecord, so the path's home rank can shade it without the scene.
#extension GL_GOOGLE_include_directive : require
#include "pt_common.glsl"
#include "bsdf.glsl"
#include "surface.glsl"
#include "texture.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialsRef { MaterialRecord materials[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    Hit hit = HitsRef(params.hits).hits[i];
    SurfaceRecord r;
    r.status = hit.status;
    r.position = vec4(0.0, 0.0, 0.0, hit.t);
    r.geometricNormal = vec4(0.0);
    r.shadingNormal = vec4(0.0);
    r.baseColor = vec4(0.0);
    r.emission = vec4(0.0);
    r.materialKind = MATERIAL_MATTE;
    r.f0 = 0.0;
    r.pad0 = 0u;
    if (hit.status == HIT_FOUND) {
        SceneDesc scene = SceneRef(params.scene).desc;
        Ray ray = RaysRef(params.rays).rays[i];
        SurfacePoint s = surfaceAt(scene, ray, hit);
        MaterialRecord rec = MaterialsRef(scene.materials).materials[s.material];
        vec3 baseColor = rec.baseColorOpacity.rgb;
        if ((rec.flags & MATERIAL_FLAG_VERTEX_COLOR) != 0u && s.hasColor) baseColor = s.color.rgb;
        if (rec.baseColorTexture != NO_TEXTURE) baseColor *= sampleTexture(scene, rec.baseColorTexture, s.texcoord).rgb;
        float f = (rec.emissiveIor.w - 1.0) / (rec.emissiveIor.w + 1.0);
        r.position.xyz = s.position;
        r.geometricNormal = vec4(s.geometricNormal, rec.baseColorOpacity.a);
        r.shadingNormal = vec4(s.shadingNormal, 0.0);
        r.baseColor = vec4(max(baseColor, vec3(0.0)), rec.metallic);
        r.emission = vec4(rec.emissiveIor.rgb, max(rec.roughness * rec.roughness, MIN_GGX_ALPHA));
        r.materialKind = rec.kind;
        r.f0 = f * f;
    }
    SurfacesRef(params.surfaces).records[i] = r;
}
