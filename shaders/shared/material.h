// Materials, textures and lights as the shading kernels read them (core::Scene converts the host
// descriptions of core/scene/SceneDescription.h into these, after validation).
#ifndef RIPPLE_SHARED_MATERIAL_H
#define RIPPLE_SHARED_MATERIAL_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint MATERIAL_MATTE = 0u;
RIPPLE_CONST uint MATERIAL_PHYSICALLY_BASED = 1u;
RIPPLE_CONST uint MATERIAL_VOLUME = 2u;  // a SurfaceRecord only: a collision in a volume (pt_volume), isotropic scattering

RIPPLE_CONST uint MATERIAL_FLAG_VERTEX_COLOR = 1u;  // the geometry's color attribute replaces baseColor
RIPPLE_CONST uint MATERIAL_FLAG_LIGHT = 2u;         // emissive with no emission texture: its triangles are lights

RIPPLE_CONST uint ALPHA_OPAQUE = 0u;  // opacity ignored
RIPPLE_CONST uint ALPHA_BLEND = 1u;   // opacity is the chance a ray stops here
RIPPLE_CONST uint ALPHA_MASK = 2u;    // opaque where opacity >= alphaCutoff, absent elsewhere

RIPPLE_CONST int NO_TEXTURE = -1;

// A material as pt_surface reads it. Texture indices name SceneDesc.textures; a float parameter from a
// texture takes the first component of the texture's output (ANARI's rule for samplers).
struct MaterialRecord {
    vec4 baseColorOpacity;  // rgb: base color (linear), w: opacity
    vec4 emissiveIor;       // rgb: emitted radiance, w: index of refraction
    uint kind;              // MATERIAL_*
    uint flags;             // MATERIAL_FLAG_*
    int baseColorTexture;   // multiplies baseColor (rgb) and opacity (a)
    uint alphaMode;         // ALPHA_*
    float metallic;
    float roughness;
    float alphaCutoff;
    float specular;         // KHR_materials_specular factor: scales the dielectric reflectance
    float transmission;     // share of the dielectric base that refracts instead of scattering diffusely
    float clearcoat;        // weight of the clear coat layer (ior 1.5)
    float clearcoatRoughness;
    int normalTexture;      // tangent-space normal map, rgb in [0,1] -> [-1,1]
    int metallicTexture;    // multiplies metallic
    int roughnessTexture;   // multiplies roughness
    int emissiveTexture;    // multiplies emissive
    int opacityTexture;     // multiplies opacity
};

RIPPLE_CONST uint TEXTURE_RGBA8_UNORM = 0u;
RIPPLE_CONST uint TEXTURE_RGBA8_SRGB = 1u;
RIPPLE_CONST uint TEXTURE_RGBA32_FLOAT = 2u;

RIPPLE_CONST uint WRAP_REPEAT = 0u;
RIPPLE_CONST uint WRAP_CLAMP_TO_EDGE = 1u;
RIPPLE_CONST uint WRAP_MIRROR_REPEAT = 2u;

// What a sampler is (core::Texture::Kind) and what it reads (core::Texture::Input).
RIPPLE_CONST uint TEXTURE_KIND_IMAGE = 0u;
RIPPLE_CONST uint TEXTURE_KIND_TRANSFORM = 1u;
RIPPLE_CONST uint TEXTURE_KIND_PRIMITIVE = 2u;
RIPPLE_CONST uint TEXTURE_INPUT_TEXCOORD = 0u;
RIPPLE_CONST uint TEXTURE_INPUT_ATTRIBUTE0 = 1u;   // ..3 follow
RIPPLE_CONST uint TEXTURE_INPUT_COLOR = 5u;
RIPPLE_CONST uint TEXTURE_INPUT_PRIMITIVE_ID = 6u;
RIPPLE_CONST uint TEXTURE_INPUT_WORLD_POSITION = 7u;
RIPPLE_CONST uint TEXTURE_INPUT_WORLD_NORMAL = 8u;

struct TextureRecord {
    uint width;
    uint height;
    uint format;            // TEXTURE_*
    uint texelOffset;       // first word in SceneDesc.texels
    uint wrapS;             // WRAP_*
    uint wrapT;
    uint linearFilter;      // 0: nearest, 1: bilinear (trilinear for 3D images)
    uint kind;              // TEXTURE_KIND_*
    uint depth;             // slices of a 3D image; 1 otherwise
    uint wrapR;
    uint inputAttribute;    // TEXTURE_INPUT_*
    uint primitiveOffset;   // TEXTURE_KIND_PRIMITIVE: added to the primitive id
    vec4 inTransform[4];    // columns, applied to the input
    vec4 inOffset;          // added after inTransform
    vec4 outTransform[4];   // columns, applied to the fetched linear RGBA (or the transformed input)
    vec4 outOffset;         // added after outTransform
};

RIPPLE_CONST uint LIGHT_DIRECTIONAL = 0u;
RIPPLE_CONST uint LIGHT_POINT = 1u;
RIPPLE_CONST uint LIGHT_QUAD = 2u;
RIPPLE_CONST uint LIGHT_SPOT = 3u;
RIPPLE_CONST uint LIGHT_RING = 4u;      // an annulus emitting with a spot profile
RIPPLE_CONST uint LIGHT_TRIANGLE = 5u;  // one triangle of emissive geometry, world space
RIPPLE_CONST uint LIGHT_HDRI = 6u;      // equirectangular environment, importance sampled

// One light in world space. Lights are ordered: the area lights that rays must test themselves (quad,
// ring, hdri; SceneDesc.testedLightCount of them) first, then the rest. selectionPdf and cdf give the
// chance next-event estimation picks each light (proportional to its power).
struct LightRecord {
    vec4 emission;          // rgb: color * intensity (irradiance, intensity or radiance by kind); w: selection pdf
    vec4 position;          // point, spot: position; quad, triangle: a corner; ring: centre; w: cdf up to this light
    vec4 direction;         // directional: unit direction light travels; quad, ring, triangle: unit normal of the
                            // front side; spot, ring: unit axis; hdri: unit direction of the image centre
    vec4 edge1;             // quad, triangle: first edge; w: area. spot, ring: x cos outer, y cos inner; ring: z radius.
                            // directional: x 1 - cos(half its angular diameter), 0 for a delta light
    vec4 edge2;             // quad, triangle: second edge. ring: w inner radius. hdri: unit up
    uint kind;              // LIGHT_*
    uint twoSided;          // quad, triangle: emits from both sides
    uint texture;           // hdri: the radiance image in SceneDesc.textures
    uint distribution;      // hdri: first word of its sampling tables in SceneDesc.texels
};

RIPPLE_GPU_END
#endif
