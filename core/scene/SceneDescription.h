// What a scene is made of, as the host sees it: meshes, sphere, cylinder and cone sets, instances of them
// with a material each, materials, textures and lights. core::Scene validates this, builds the BVHs and
// uploads the flat GPU scene of shaders/shared/scene.h. Everything is in world units; lights are in world
// space (the ANARI layer applies instance transforms to lights before they get here).
#pragma once

#include "core/scene/AmrGrid.h"
#include "core/scene/NanoVdbGrid.h"
#include "core/scene/UnstructuredGrid.h"
#include "shaders/shared/material.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace ripple::core {

// Identity of a geometry across scene updates: a Scene constructed with the previous Scene as `previous`
// reuses the BLAS of a geometry whose key and version are both unchanged (see Scene.h). key 0 means
// "no identity": always rebuilt.
struct GeometryIdentity {
    uint64_t key = 0;
    uint64_t version = 0;
};

// One of a geometry's ANARI attribute0..3: a value per vertex (interpolated across a triangle and along a
// cylinder or cone; a sphere's vertex is its centre, so per vertex is per sphere), per primitive (as the
// application numbered them: quads, not their triangles) or one for the whole geometry. Samplers and
// materials read them (Texture::Input). A wrong length is reported and the attribute ignored.
struct GeometryAttribute {
    enum class Rate : uint32_t { Vertex = 0, Primitive = 1, Uniform = 2 };  // shared/scene.h ATTRIBUTE_RATE_*
    Rate rate = Rate::Vertex;
    std::vector<glm::vec4> values;        // empty: the geometry has no such attribute
};
using GeometryAttributes = std::array<GeometryAttribute, 4>;

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;      // empty: consecutive position triples form the triangles
    // Optional attributes; each is empty or has exactly one entry per position (per triangle for
    // primitiveColors). A wrong length is reported and the attribute ignored.
    std::vector<glm::vec3> normals;       // shading normals, object space
    std::vector<glm::vec4> colors;        // the ANARI "color" attribute, linear RGBA
    std::vector<glm::vec2> texcoords;     // glTF/ANARI texcoord (attribute "texcoord")
    // Tangents for normal maps: xyz along increasing texcoord u, w the handedness (the bitangent is
    // w * cross(normal, tangent)). Empty: derived from the texcoords, handedness +1.
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec4> primitiveColors;
    // Quads are split into two triangles by the ANARI layer; it sets this to 2 so that the primitive id a
    // frame reports is triangle / 2. 1 for plain triangle meshes.
    uint32_t trianglesPerPrimitive = 1;
    GeometryAttributes attributes;
    GeometryIdentity identity;            // last, so positional initialisers stay short
};

struct SphereSet {
    std::vector<glm::vec3> centers;
    std::vector<float> radii;             // one per center, or a single radius for all
    std::vector<glm::vec4> colors;        // empty, or one per sphere
    GeometryAttributes attributes;
    GeometryIdentity identity;
};

// Which ends of a cylinder or cone a flat disk closes (the ANARI "caps" parameter).
enum class CapEnds : uint32_t { None = 0, First = 1, Second = 2, Both = 3 };

// Round cylinders between two points; caps close the ends named.
struct CylinderSet {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec2> indices;      // empty: consecutive position pairs form the cylinders
    std::vector<float> radii;             // one per cylinder, or a single radius for all
    std::vector<glm::vec4> colors;        // empty, or one per cylinder
    CapEnds caps = CapEnds::None;
    std::vector<CapEnds> segmentCaps;     // empty, or one per cylinder (replacing `caps`)
    GeometryAttributes attributes;        // per vertex: one per position
    GeometryIdentity identity;
};

// Cone frusta between two points with a radius at each end (ANARI "cone"), or, when `round`, a curve of
// round linear segments (ANARI "curve"): a sphere at each end of a segment, joined by the cone tangent to
// both, so consecutive segments meet smoothly. Radii are per position (or a single one for all); a radius
// may be 0 at one end of a cone (its apex), never at both.
struct ConeSet {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec2> indices;      // empty: consecutive position pairs form the segments
    std::vector<float> radii;             // one per position, or a single radius for all
    std::vector<glm::vec4> colors;        // empty, or one per segment
    CapEnds caps = CapEnds::None;         // cones only: a round segment has no caps
    std::vector<CapEnds> segmentCaps;     // cones only: empty, or one per cone (replacing `caps`)
    bool round = false;
    GeometryAttributes attributes;        // per vertex: one per position
    GeometryIdentity identity;
};

// Iso-surfaces of a structured-regular scalar field (ANARI geometry "isosurface"): where the trilinear
// interpolant of the cell-vertex samples equals one of the isovalues. Voxel (i, j, k) sits at
// origin + (i, j, k) * spacing; the primitive id a frame reports is the isovalue's index. Cells with a
// NaN or Inf corner are left out (reported).
struct IsosurfaceSet {
    // Set: the field is this unstructured mesh's (dims, values, origin and spacing are unused), whose cells
    // the surface is found in by root finding on their own interpolant (shaders/unstructured.glsl).
    std::shared_ptr<const UnstructuredGrid> mesh;
    glm::uvec3 dims{0};
    std::vector<float> values;            // dims.x * dims.y * dims.z, x fastest
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};              // each component finite and positive
    std::vector<float> isovalues;         // finite
    std::vector<glm::vec4> colors;        // empty, or one per isovalue
    GeometryAttributes attributes;        // per primitive (one per isovalue) or uniform
    GeometryIdentity identity;
};

enum class GeometryKind : uint32_t { Triangles = 0, Spheres = 1, Cylinders = 2, Cones = 3, Isosurfaces = 4 };

struct GeometryRef {
    GeometryKind kind = GeometryKind::Triangles;
    uint32_t index = 0;                   // into SceneDescription::meshes, ::sphereSets, ::cylinderSets, ::coneSets
                                          // or ::isosurfaceSets
};

// A sampler as materials read it: an input from the surface, mapped to linear RGBA. Image texels are
// row-major, then slice after slice, with row 0 at texture coordinate v = 0.
struct Texture {
    // Image: a 1D/2D/3D image read at inTransform * input + inOffset. Transform: no image, the output is
    // the transformed input. Primitive: texel (primitive id + primitiveOffset) of a one-row image, nearest.
    enum class Kind : uint32_t { Image = 0, Transform = 1, Primitive = 2 };
    // The surface value a sampler reads (values of shared/material.h TEXTURE_INPUT_*). Absent attributes
    // read as (0, 0, 0, 1); Texcoord is (u, v, 0, 1); PrimitiveId is (id, 0, 0, 1).
    enum class Input : uint32_t {
        Texcoord = 0, Attribute0 = 1, Attribute1 = 2, Attribute2 = 3, Attribute3 = 4, Color = 5,
        PrimitiveId = 6, WorldPosition = 7, WorldNormal = 8
    };
    enum class Format : uint32_t { Rgba8Unorm = 0, Rgba8Srgb = 1, Rgba32Float = 2 };
    enum class Wrap : uint32_t { Repeat = 0, ClampToEdge = 1, MirrorRepeat = 2 };
    Kind kind = Kind::Image;
    Input input = Input::Texcoord;
    uint32_t width = 0;                   // Transform: 0 (no image)
    uint32_t height = 0;
    uint32_t depth = 1;                   // slices of a 3D image; 1 otherwise
    Format format = Format::Rgba8Unorm;
    std::vector<uint8_t> texels;          // width * height * depth * (4 or 16) bytes
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
    Wrap wrapR = Wrap::ClampToEdge;
    bool linearFilter = true;             // false: nearest
    glm::mat4 inTransform{1.0f};          // applied to the input before lookup
    glm::vec4 inOffset{0.0f};             // added after inTransform
    glm::mat4 outTransform{1.0f};         // applied to the fetched RGBA (or, for Transform, the input)
    glm::vec4 outOffset{0.0f};            // added after outTransform
    uint32_t primitiveOffset = 0;         // Primitive: added to the primitive id
};

inline constexpr int32_t kNoTexture = -1;

struct Material {
    enum class Kind : uint32_t { Matte = 0, PhysicallyBased = 1 };
    // Blend: opacity is the chance a ray stops (the default, so opacity works without naming a mode);
    // Opaque: opacity ignored; Mask: opaque where opacity >= alphaCutoff, absent elsewhere.
    enum class AlphaMode : uint32_t { Opaque = 0, Blend = 1, Mask = 2 };
    Kind kind = Kind::Matte;
    glm::vec3 baseColor{0.8f};
    bool baseColorFromVertexColor = false; // the ANARI "color" attribute replaces baseColor
    int32_t baseColorTexture = kNoTexture; // index into SceneDescription::textures (multiplies baseColor
                                           // and, by its alpha, opacity)
    float opacity = 1.0f;
    AlphaMode alphaMode = AlphaMode::Blend;
    float alphaCutoff = 0.5f;
    float metallic = 1.0f;                 // physicallyBased only (ANARI default 1)
    float roughness = 1.0f;                // physicallyBased only
    glm::vec3 emissive{0.0f};              // radiance emitted, linear RGB (already times any strength)
    float ior = 1.5f;
    // physicallyBased extensions (glTF KHR_materials_*): 0 turns each off, except specular (1: the F0 of
    // the ior as it is).
    float specular = 1.0f;                 // scales the dielectric reflectance at normal incidence
    float transmission = 0.0f;
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    // Textures (indices into SceneDescription::textures) for the other parameters; a float parameter takes
    // the texture's first output component and is multiplied by it.
    int32_t normalTexture = kNoTexture;    // tangent-space normal map (needs texcoords), rgb in [0,1]
    int32_t metallicTexture = kNoTexture;
    int32_t roughnessTexture = kNoTexture;
    int32_t emissiveTexture = kNoTexture;  // rgb multiplies emissive; such surfaces are not lights
    int32_t opacityTexture = kNoTexture;
};

// Whether an instance transform can be traced: finite, affine (last row 0 0 0 1) and invertible. Instances
// that fail it are skipped and reported (Scene), and their emitters are no lights (LightTable).
inline bool affineAndInvertible(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;
    return std::abs(glm::determinant(glm::dmat3(glm::mat3(m)))) > 1e-30;
}

struct InstanceDescription {
    GeometryRef geometry;
    glm::mat4 transform{1.0f};            // object to world; must be affine and invertible
    uint32_t materialIndex = 0;           // into SceneDescription::materials; out of range: default matte
    uint32_t objectId = 0;                // the application's id of the surface (objectId channel)
    uint32_t instanceId = 0;              // the application's id of the instance (instanceId channel)
    // The instance's uniform "color" and attribute0..3: where set, they replace the geometry's own.
    std::optional<glm::vec4> color;
    std::array<std::optional<glm::vec4>, 4> attributes;
};

struct Light {
    enum class Kind : uint32_t { Directional = 0, Point = 1, Quad = 2, Spot = 3, Ring = 4, Hdri = 6 };
    Kind kind = Kind::Directional;
    glm::vec3 color{1.0f};
    // Directional: irradiance (W/m^2) on a surface facing the light. Point, spot: intensity (W/sr).
    // Quad, ring: radiance (W/sr/m^2) of its emitting side(s). Hdri: scale of the image's radiance.
    float intensity = 1.0f;
    glm::vec3 position{0.0f};             // point, spot, ring (centre) and quad (a corner of the quad)
    // Directional: the direction light travels. Spot, ring: the axis light leaves along. Hdri: the
    // direction the centre of the image is seen in.
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 edge1{1.0f, 0.0f, 0.0f};    // quad: position + s*edge1 + t*edge2, s,t in [0,1]
    glm::vec3 edge2{0.0f, 1.0f, 0.0f};
    bool twoSided = false;                // quad: emits from both sides (else along cross(edge1, edge2))
    // Spot, ring: full light within openingAngle / 2 - falloffAngle of the axis, none beyond
    // openingAngle / 2, smooth between (ANARI's definition). Radians.
    float openingAngle = 3.14159265f;
    float falloffAngle = 0.1f;
    float radius = 0.0f;                  // ring: outer radius (0: a spot light)
    float innerRadius = 0.0f;             // ring
    glm::vec3 up{0.0f, 0.0f, 1.0f};       // hdri: the direction of the image's top row
    // Directional: the apparent diameter of the light's disc, radians, in [0, pi]; 0 is a delta light (a
    // sun that no ray can hit). Within the disc the radiance is uniform, irradiance / (pi sin^2(d / 2)).
    float angularDiameter = 0.0f;
    int32_t texture = kNoTexture;         // hdri: an equirectangular Rgba32Float texture (its radiance)
};

// A structured-regular scalar field (or an unstructured mesh's, a NanoVDB grid's or an AMR hierarchy's) seen
// through a 1D transfer function (ANARI spatialField "structuredRegular", "unstructured", "nanovdb" or "amr" inside a volume "transferFunction1D"), placed in the world by `transform`. Values are
// cell-vertex samples: voxel (i, j, k) sits at origin + (i, j, k) * spacing in object space, so the field
// spans origin .. origin + (dims - 1) * spacing. Opacity o means transmittance 1 - o over unitDistance
// world units (extinction -ln(1 - o) / unitDistance); the colour is the single-scattering albedo.
struct Volume {
    glm::uvec3 dims{0};
    // dims.x * dims.y * dims.z, x fastest; shared with whoever made them (never changed once shared).
    std::shared_ptr<const std::vector<float>> values;
    // Set: the field is this unstructured mesh instead (dims, values, origin, spacing and linearFilter are
    // unused; the mesh is placed in object space by its own vertices).
    std::shared_ptr<const UnstructuredGrid> unstructured;
    // Set: the field is this NanoVDB grid instead (dims, values, origin and spacing unused; its own map places
    // it in object space; linearFilter applies).
    std::shared_ptr<const NanoVdbGrid> nanovdb;
    // Set: the field is this AMR hierarchy instead (dims, values, origin, spacing and linearFilter unused; its
    // own origin and spacing place it in object space; the finest covering cell's value is taken).
    std::shared_ptr<const AmrGrid> amr;
    // Nonzero key: the same (key, version) as a volume of a Scene's `previous` means the same values, and
    // their device buffer is reused (a transfer-function edit uploads no voxels). Zero: always uploaded.
    GeometryIdentity voxelIdentity;
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};
    bool linearFilter = true;             // false: nearest voxel
    glm::vec2 valueRange{0.0f, 1.0f};     // maps to the ends of the colour and opacity arrays
    std::vector<glm::vec3> colors;        // linear RGB spread evenly over the value range; empty: white
    std::vector<float> opacities;         // likewise; empty: 1
    float unitDistance = 1.0f;
    glm::mat4 transform{1.0f};            // object to world; must be affine and invertible
    uint32_t objectId = ~0u;              // the application's ids (objectId, instanceId channels); ~0u: unset
    uint32_t instanceId = ~0u;
};

struct SceneDescription {
    std::vector<TriangleMesh> meshes;
    std::vector<SphereSet> sphereSets;
    std::vector<CylinderSet> cylinderSets;
    std::vector<ConeSet> coneSets;
    std::vector<IsosurfaceSet> isosurfaceSets;
    std::vector<InstanceDescription> instances;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    std::vector<Volume> volumes;
    // Radius of the sphere directional and hdri lights' power is measured through (their chance of being
    // picked). 0: half the diagonal of this scene's bounds. A data-parallel rank sets the whole world's.
    float lightSceneRadius = 0.0f;
    // Largest |coordinate| of the whole world, which ray-origin offsets near 0 scale with (Scene.cpp). 0:
    // this scene's own. A data-parallel rank sets the whole world's, so every rank offsets as one would.
    float worldMagnitude = 0.0f;
    // Data-parallel: the other ranks' emissive-triangle lights (Scene::triangleLights() there), added to
    // this rank's light table so that every rank samples every emitter and weighs its hits alike.
    std::vector<gpu::LightRecord> foreignTriangleLights;
};

}  // namespace ripple::core
