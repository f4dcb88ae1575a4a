// A glTF 2.0 file (.gltf or .glb) read into a validated, plain C++ scene: meshes, their instances, materials,
// textures, cameras and punctual lights. No ANARI here, so ripple-bench reads meshes through it too.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

// Every problem that stops a file from loading. The message names the file and the element
// ("scene.glb: mesh 0 primitive 2: accessor 7 (indices): index 12034 out of range for 900 vertices").
class GltfError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Vertex and index data of TRIANGLES primitives. Primitives that name the same accessors share one
// geometry, so data stored once in the file is imported once. Attributes are empty or hold exactly one
// entry per position.
struct GltfGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords;   // TEXCOORD_0, glTF convention: v = 0 is the top row of an image
    std::vector<glm::vec4> colors;      // COLOR_0, linear RGBA (RGB files get alpha 1)
    std::vector<glm::uvec3> indices;    // always filled: a non-indexed primitive gets 0, 1, 2, ...
};

// A geometry with a material: one glTF primitive.
struct GltfPrimitive {
    uint32_t geometry = 0;              // index into GltfScene::geometries
    int32_t material = -1;              // index into GltfScene::materials; -1 is glTF's default material
};

struct GltfMesh {
    std::string name;
    std::vector<GltfPrimitive> primitives;
};

// A node that draws a mesh. Many instances may share one mesh.
struct GltfMeshInstance {
    uint32_t mesh = 0;
    uint32_t node = 0;
    glm::mat4 transform{1.0f};          // object to world, the node's ancestors included
};

// RGBA8, row 0 first as stored in the file (the row at v = 0). Empty when images were not decoded or the
// image could not be (a warning says which).
struct GltfImage {
    std::string name;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};

enum class GltfWrap { Repeat, ClampToEdge, MirroredRepeat };

struct GltfTexture {
    uint32_t image = 0;
    GltfWrap wrapS = GltfWrap::Repeat;
    GltfWrap wrapT = GltfWrap::Repeat;
    bool linearFilter = true;           // magnification filter; false: nearest
};

enum class GltfAlphaMode { Opaque, Mask, Blend };

// Metallic-roughness material. Texture fields index GltfScene::textures, -1 for none; textures that read
// a texture coordinate set other than 0 are dropped with a warning.
struct GltfMaterial {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int32_t baseColorTexture = -1;      // sRGB; multiplied by baseColorFactor
    float metallic = 1.0f;
    float roughness = 1.0f;
    int32_t metallicRoughnessTexture = -1; // linear; roughness in G, metallic in B
    int32_t normalTexture = -1;
    glm::vec3 emissive{0.0f};           // emissiveFactor times KHR_materials_emissive_strength
    int32_t emissiveTexture = -1;       // sRGB; multiplied by emissive
    GltfAlphaMode alphaMode = GltfAlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
};

// A camera as placed by its node: glTF cameras look down their local -Z with +Y up.
struct GltfCamera {
    enum class Kind { Perspective, Orthographic };
    std::string name;
    Kind kind = Kind::Perspective;
    float yfov = 0.0f;                  // perspective: vertical field of view, radians
    float aspectRatio = 0.0f;           // perspective: 0 when the file leaves it to the viewport
    float xmag = 0.0f, ymag = 0.0f;     // orthographic: half width and half height
    float znear = 0.0f;
    float zfar = 0.0f;                  // 0: infinite
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
};

// KHR_lights_punctual, placed by its node. Units as in glTF: lux for directional, candela otherwise.
struct GltfLight {
    enum class Kind { Directional, Point, Spot };
    std::string name;
    Kind kind = Kind::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;                 // 0: infinite
    float innerConeAngle = 0.0f;        // spot: half angles, radians
    float outerConeAngle = 0.7853982f;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f}; // the direction light travels (local -Z)
    // Directional: apparent diameter, radians (ANARI's "angularDiameter"). glTF has none (0, a delta
    // light); the studio light of unlit scenes is a sun of this size.
    float angularDiameter = 0.0f;
};

struct GltfScene {
    std::filesystem::path file;
    std::vector<GltfGeometry> geometries;
    std::vector<GltfMesh> meshes;
    std::vector<GltfMeshInstance> instances;
    std::vector<GltfMaterial> materials;
    std::vector<GltfTexture> textures;
    std::vector<GltfImage> images;
    std::vector<GltfCamera> cameras;    // one per camera node, in node order of the scene
    std::vector<GltfLight> lights;      // one per light node
    std::vector<std::string> warnings;  // what was skipped, each naming the element
    glm::vec3 boundsMin{0.0f};          // world bounds of all instances; min > max when nothing is drawn
    glm::vec3 boundsMax{-1.0f};

    uint64_t trianglesStored() const;   // over geometries, each counted once
    uint64_t trianglesDrawn() const;    // over instances
};

struct GltfLoadOptions {
    bool decodeImages = true;           // false: images stay empty (geometry-only readers)
    // Per file: the scene file and each buffer or image file it names. Larger files are refused unread.
    uint64_t maxFileBytes = uint64_t(1) << 30;
    uint32_t maxNodeDepth = 1024;       // deeper hierarchies are rejected rather than overflow the stack
    uint64_t maxImagePixels = uint64_t(1) << 27; // per image; larger ones are rejected, not allocated
    // JSON nesting (arrays and objects) allowed, checked before any parser sees the file: parsers recurse.
    uint32_t maxJsonDepth = 512;
    // The folder that buffer and image URIs may not leave (after `..` and symlinks are resolved). Empty: the
    // scene file's own folder. A wider folder is for trusted input only (docs/gltf-security.md).
    std::filesystem::path resourceRoot;
};

// Reads the default scene (scene 0 where none is named; every root node where the file has no scenes).
// Throws GltfError on anything malformed.
GltfScene loadGltf(const std::filesystem::path& file, const GltfLoadOptions& options = {});

}  // namespace ripple::apps
