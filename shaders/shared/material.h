// Materials, textures and lights as the shading kernels read them (core::Scene converts the host
// descriptions of core/scene/SceneDescription.h into these, after validation).
#ifndef RIPPLE_SHARED_MATERIAL_H
#define RIPPLE_SHARED_MATERIAL_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint MATERIAL_MATTE = 0u;
RIPPLE_CONST uint MATERIAL_PHYSICALLY_BASED = 1u;

RIPPLE_CONST uint MATERIAL_FLAG_VERTEX_COLOR = 1u;  // the geometry's color attribute replaces baseColor

RIPPLE_CONST int NO_TEXTURE = -1;

struct MaterialRecord {
    vec4 baseColorOpacity;  // rgb: base color (linear), w: opacity
    vec4 emissiveIor;       // rgb: emitted radiance, w: index of refraction
    uint kind;              // MATERIAL_*
    uint flags;             // MATERIAL_FLAG_*
    int baseColorTexture;   // index into SceneDesc.textures, or NO_TEXTURE
    uint pad0;
    float metallic;
    float roughness;
    float pad1;
    float pad2;
};

RIPPLE_CONST uint TEXTURE_RGBA8_UNORM = 0u;
RIPPLE_CONST uint TEXTURE_RGBA8_SRGB = 1u;
RIPPLE_CONST uint TEXTURE_RGBA32_FLOAT = 2u;

RIPPLE_CONST uint WRAP_REPEAT = 0u;
RIPPLE_CONST uint WRAP_CLAMP_TO_EDGE = 1u;
RIPPLE_CONST uint WRAP_MIRROR_REPEAT = 2u;

struct TextureRecord {
    uint width;
    uint height;
    uint format;            // TEXTURE_*
    uint texelOffset;       // first word in SceneDesc.texels
    uint wrapS;             // WRAP_*
    uint wrapT;
    uint linearFilter;      // 0: nearest, 1: bilinear
    uint pad0;
    vec4 inTransform[4];    // columns, applied to (u, v, 0, 1)
    vec4 outTransform[4];   // columns, applied to the fetched linear RGBA
};

RIPPLE_CONST uint LIGHT_DIRECTIONAL = 0u;
RIPPLE_CONST uint LIGHT_POINT = 1u;
RIPPLE_CONST uint LIGHT_QUAD = 2u;

struct LightRecord {
    vec4 emission;          // rgb: color * intensity (irradiance, intensity or radiance by kind)
    vec4 position;          // point: position; quad: a corner
    vec4 direction;         // directional: unit direction light travels; quad: unit normal of the front side
    vec4 edge1;             // quad: first edge; w: area
    vec4 edge2;             // quad: second edge
    uint kind;              // LIGHT_*
    uint twoSided;          // quad: emits from both sides
    uint pad0;
    uint pad1;
};

RIPPLE_GPU_END
#endif
