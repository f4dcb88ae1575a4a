// ANARI samplers at a surface point: the input a sampler reads (texcoord, attribute0..3, color, primitive
// id, world position or normal), then an image lookup, the primitive's array entry, or the input itself,
// and the output transform. Needs pt_common.glsl, surface.glsl and texture.glsl.
#ifndef RIPPLE_SAMPLER_GLSL
#define RIPPLE_SAMPLER_GLSL

// An instance's uniform attribute replaces the geometry's. Absent attributes read as (0, 0, 0, 1), ANARI's
// rule for missing components.
vec4 samplerInput(SceneDesc scene, SurfacePoint s, uint which) {
    if (which == TEXTURE_INPUT_TEXCOORD) return vec4(s.texcoord, 0.0, 1.0);
    if (which == TEXTURE_INPUT_COLOR) return s.hasColor ? s.color : vec4(0.0, 0.0, 0.0, 1.0);
    if (which == TEXTURE_INPUT_PRIMITIVE_ID) return vec4(float(s.primitiveId), 0.0, 0.0, 1.0);
    if (which == TEXTURE_INPUT_WORLD_POSITION) return vec4(s.position, 1.0);
    if (which == TEXTURE_INPUT_WORLD_NORMAL) return vec4(s.shadingNormal, 0.0);
    uint a = min(which - TEXTURE_INPUT_ATTRIBUTE0, 3u);
    InstanceShading inst = InstanceShadingRef(scene.instanceShading).instances[s.instance];
    if ((inst.attributeMask & (INSTANCE_ATTRIBUTE_0 << a)) != 0u) return attributeAt(scene, inst.attributeOffset, 1u + a);
    GeometryRecord geom = GeometriesRef(scene.geometries).geometries[s.geometry];
    uint offset = geom.attributeOffset[a];
    if (offset == NO_ATTRIBUTE) return vec4(0.0, 0.0, 0.0, 1.0);
    uint rate = (geom.attributeRates >> (2u * a)) & 3u;
    if (rate == ATTRIBUTE_RATE_UNIFORM) return attributeAt(scene, offset, 0u);
    if (rate == ATTRIBUTE_RATE_PRIMITIVE) return attributeAt(scene, offset, s.primitiveId);
    return interpolate(scene, offset, s.vertices, s.bary);
}

vec4 sampleTexture(SceneDesc scene, int textureIndex, SurfacePoint s) {
    TextureRecord tex = TexturesRef(scene.textures).textures[textureIndex];
    vec4 value;
    if (tex.kind == TEXTURE_KIND_PRIMITIVE) {
        // Integer indexing (a float coordinate would round ids past 2^24), clamped to the last entry
        // without overflowing id + offset.
        uint last = tex.width - 1u;
        uint index = tex.primitiveOffset >= last ? last : min(s.primitiveId, last - tex.primitiveOffset) + tex.primitiveOffset;
        value = fetchTexel(tex, scene.texels, int(index), 0);
    } else {
        mat4 inTransform = mat4(tex.inTransform[0], tex.inTransform[1], tex.inTransform[2], tex.inTransform[3]);
        value = inTransform * samplerInput(scene, s, tex.inputAttribute) + tex.inOffset;
        if (tex.kind == TEXTURE_KIND_IMAGE) value = sampleImage(tex, scene.texels, value.xyz);
    }
    mat4 outTransform = mat4(tex.outTransform[0], tex.outTransform[1], tex.outTransform[2], tex.outTransform[3]);
    return outTransform * value + tex.outOffset;
}

#endif
