// The built-in demo scenes: procedural meshes (tiled floor, boxes, torus), sphere and cylinder geometries,
// matte and physically based materials, a sun, an area light and a camera, all through standard ANARI.
#include "apps/scene/DemoScene.h"

#include "apps/scene/AnariParams.h"
#include "apps/scene/SceneEdits.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

namespace ripple::apps {

using anari::set;
using anari::setObject;

namespace {

struct MeshData {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::uvec3> indices;
    std::vector<glm::vec4> primitiveColors;   // empty, or one per triangle

    // A parallelogram corner + s*edge1 + t*edge2 facing along cross(edge1, edge2).
    void quad(const glm::vec3& corner, const glm::vec3& edge1, const glm::vec3& edge2) {
        const uint32_t base = uint32_t(positions.size());
        const glm::vec3 n = glm::normalize(glm::cross(edge1, edge2));
        for (const glm::vec3& p : {corner, corner + edge1, corner + edge1 + edge2, corner + edge2}) {
            positions.push_back(p);
            normals.push_back(n);
        }
        indices.emplace_back(base, base + 1, base + 2);
        indices.emplace_back(base, base + 2, base + 3);
    }

    // The unit cube [-0.5, 0.5]^3 under `transform` (rotation, scale, translation), faces outward.
    void box(const glm::mat4& transform) {
        const auto at = [&](float x, float y, float z) { return glm::vec3(transform * glm::vec4(x, y, z, 1.0f)); };
        const glm::vec3 o = at(-0.5f, -0.5f, -0.5f);
        const glm::vec3 x = at(0.5f, -0.5f, -0.5f) - o, y = at(-0.5f, 0.5f, -0.5f) - o, z = at(-0.5f, -0.5f, 0.5f) - o;
        quad(o, y, x);            // -Z
        quad(o + z, x, y);        // +Z
        quad(o, z, y);            // -X
        quad(o + x, y, z);        // +X
        quad(o, x, z);            // -Y
        quad(o + y, z, x);        // +Y
    }
};

// A square floor at y = 0 of tiles x tiles squares in two alternating colours (per-triangle colours).
MeshData tiledFloor(float halfExtent, int tiles, const glm::vec3& a, const glm::vec3& b) {
    MeshData mesh;
    const float step = 2.0f * halfExtent / float(tiles);
    for (int i = 0; i < tiles; ++i)
        for (int j = 0; j < tiles; ++j) {
            mesh.quad(glm::vec3(-halfExtent + float(i) * step, 0.0f, -halfExtent + float(j) * step),
                      glm::vec3(0.0f, 0.0f, step), glm::vec3(step, 0.0f, 0.0f));
            const glm::vec4 c((i + j) % 2 ? a : b, 1.0f);
            mesh.primitiveColors.insert(mesh.primitiveColors.end(), {c, c});
        }
    return mesh;
}

// A torus around the local Y axis (ring radius R, tube radius r), placed by `transform`.
MeshData torus(float R, float r, int segments, int sides, const glm::mat4& transform) {
    MeshData mesh;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    for (int i = 0; i <= segments; ++i) {
        const float u = glm::two_pi<float>() * float(i) / float(segments);
        for (int j = 0; j <= sides; ++j) {
            const float v = glm::two_pi<float>() * float(j) / float(sides);
            const glm::vec3 ring(std::cos(u), 0.0f, std::sin(u));
            const glm::vec3 n = std::cos(v) * ring + glm::vec3(0.0f, std::sin(v), 0.0f);
            mesh.positions.push_back(glm::vec3(transform * glm::vec4(R * ring + r * n, 1.0f)));
            mesh.normals.push_back(glm::normalize(normalMatrix * n));
        }
    }
    const uint32_t row = uint32_t(sides + 1);
    for (uint32_t i = 0; i < uint32_t(segments); ++i)
        for (uint32_t j = 0; j < uint32_t(sides); ++j) {
            const uint32_t a = i * row + j, b = (i + 1) * row + j;
            mesh.indices.emplace_back(a, a + 1, b);
            mesh.indices.emplace_back(b, a + 1, b + 1);
        }
    return mesh;
}

class DemoBuilder {
public:
    // extraLights (owned by the caller) join the scene's own lights in the world. edits: where given, the
    // lights, volumes and iso-surfaces made here are listed there.
    DemoBuilder(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits)
        : d_(d), handles_(d), lights_(extraLights), edits_(edits) {}

    ANARIMaterial matte(const glm::vec3& color) {
        ANARIMaterial m = handles_.keep(anariNewMaterial(d_, "matte"), "matte material");
        set(d_, m, "color", color);
        anariCommitParameters(d_, m);
        return m;
    }

    // Matte whose colour comes from the geometry's color attribute (per vertex or per primitive).
    ANARIMaterial matteFromColors() {
        ANARIMaterial m = handles_.keep(anariNewMaterial(d_, "matte"), "matte material");
        set(d_, m, "color", "color");
        anariCommitParameters(d_, m);
        return m;
    }

    ANARIMaterial pbr(const glm::vec3& baseColor, float metallic, float roughness) {
        ANARIMaterial m = handles_.keep(anariNewMaterial(d_, "physicallyBased"), "physicallyBased material");
        set(d_, m, "baseColor", baseColor);
        set(d_, m, "metallic", metallic);
        set(d_, m, "roughness", roughness);
        anariCommitParameters(d_, m);
        return m;
    }

    void mesh(const MeshData& data, ANARIMaterial material) {
        ANARIGeometry g = handles_.keep(anariNewGeometry(d_, "triangle"), "triangle geometry");
        attach(g, "vertex.position", data.positions);
        attach(g, "vertex.normal", data.normals);
        attach(g, "primitive.index", data.indices);
        if (!data.primitiveColors.empty()) attach(g, "primitive.color", data.primitiveColors);
        surface(g, material);
    }

    void spheres(const std::vector<glm::vec3>& centers, float radius, ANARIMaterial material) {
        ANARIGeometry g = handles_.keep(anariNewGeometry(d_, "sphere"), "sphere geometry");
        attach(g, "vertex.position", centers);
        set(d_, g, "radius", radius);
        surface(g, material);
    }

    // Capped cylinders between consecutive pairs of `ends`.
    void cylinders(const std::vector<glm::vec3>& ends, float radius, ANARIMaterial material) {
        ANARIGeometry g = handles_.keep(anariNewGeometry(d_, "cylinder"), "cylinder geometry");
        attach(g, "vertex.position", ends);
        set(d_, g, "radius", radius);
        set(d_, g, "caps", "both");
        surface(g, material);
    }

    void directionalLight(const glm::vec3& direction, const glm::vec3& color, float irradiance) {
        ANARILight l = handles_.keep(anariNewLight(d_, "directional"), "directional light");
        set(d_, l, "direction", glm::normalize(direction));
        set(d_, l, "color", color);
        set(d_, l, "irradiance", irradiance);
        anariCommitParameters(d_, l);
        lights_.push_back(l);
        if (edits_) edits_->add({l, "sun", "directional", color, irradiance, glm::normalize(direction), 0.0f});
    }

    // Emits from the side cross(edge1, edge2) points to.
    void quadLight(const glm::vec3& corner, const glm::vec3& edge1, const glm::vec3& edge2, const glm::vec3& color,
                   float radiance) {
        ANARILight l = handles_.keep(anariNewLight(d_, "quad"), "quad light");
        set(d_, l, "position", corner);
        set(d_, l, "edge1", edge1);
        set(d_, l, "edge2", edge2);
        set(d_, l, "color", color);
        set(d_, l, "radiance", radiance);
        set(d_, l, "side", "front");
        anariCommitParameters(d_, l);
        lights_.push_back(l);
        if (edits_) edits_->add({l, "quad light", "quad", color, radiance, std::nullopt, 0.0f});
    }

    // A structuredRegular field of FLOAT32 samples (x fastest) spanning [lo, hi]. `values`: the smallest and
    // largest sample of the whole field where these are a slab of it (the panels' ranges), else these.
    ANARISpatialField field(glm::uvec3 dims, const std::vector<float>& samples, const glm::vec3& lo, const glm::vec3& hi,
                            std::optional<glm::vec2> values = std::nullopt) {
        ANARIArray3D data = handles_.keep(anariNewArray3D(d_, nullptr, nullptr, nullptr, ANARI_FLOAT32, dims.x, dims.y, dims.z),
                                          "3D array");
        void* mapped = anariMapArray(d_, data);
        if (!mapped) throw std::runtime_error("the ANARI device could not map a new 3D array");
        std::memcpy(mapped, samples.data(), samples.size() * sizeof(float));
        anariUnmapArray(d_, data);
        ANARISpatialField field = handles_.keep(anariNewSpatialField(d_, "structuredRegular"), "spatial field");
        setObject(d_, field, "data", ANARI_ARRAY3D, data);
        set(d_, field, "origin", lo);
        set(d_, field, "spacing", (hi - lo) / glm::vec3(dims - 1u));
        anariCommitParameters(d_, field);
        if (!values) {
            const auto [smallest, largest] = std::minmax_element(samples.begin(), samples.end());
            values = samples.empty() ? glm::vec2(0.0f, 1.0f) : glm::vec2(*smallest, *largest);
        }
        fieldRanges_[field] = *values;
        return field;
    }

    // An unstructured field of `mesh`'s cells and values, its vertices placed at p * scale + offset.
    // `values`: the whole mesh's smallest and largest value where this is a part of it (the panels' ranges).
    ANARISpatialField unstructuredField(const UnstructuredMesh& mesh, float scale, const glm::vec3& offset, glm::vec2 values) {
        std::vector<glm::vec3> positions(mesh.positions.size());
        for (size_t v = 0; v < positions.size(); ++v) positions[v] = mesh.positions[v] * scale + offset;
        ANARISpatialField field = handles_.keep(anariNewSpatialField(d_, "unstructured"), "spatial field");
        attach(field, "vertex.position", positions);
        attach(field, mesh.cellCentered ? "cell.data" : "vertex.data", mesh.values);
        attach(field, "index", mesh.index);
        attach(field, "cell.index", mesh.cellIndex);
        attach(field, "cell.type", mesh.cellType);
        anariCommitParameters(d_, field);
        fieldRanges_[field] = values;
        return field;
    }

    // A nanovdb field of the grid buffer `grid`; `values`: its smallest and largest value (the panels' ranges).
    ANARISpatialField nanovdbField(const std::vector<uint8_t>& grid, glm::vec2 values) {
        ANARISpatialField field = handles_.keep(anariNewSpatialField(d_, "nanovdb"), "spatial field");
        setObject(d_, field, "data", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, grid, ANARI_UINT8), "array"));
        anariCommitParameters(d_, field);
        fieldRanges_[field] = values;
        return field;
    }

    // An "amr" field holding `amr`'s blocks (each block's values an ARRAY3D).
    ANARISpatialField amrField(const AmrData& amr, glm::vec2 values) {
        ANARISpatialField field = handles_.keep(anariNewSpatialField(d_, "amr"), "spatial field");
        std::vector<int32_t> levels;
        std::vector<std::array<int32_t, 6>> bounds;
        ANARIArray1D data = handles_.keep(anariNewArray1D(d_, nullptr, nullptr, nullptr, ANARI_ARRAY3D, amr.blocks.size()), "array");
        auto* blockArrays = static_cast<ANARIArray3D*>(anariMapArray(d_, data));
        for (size_t i = 0; i < amr.blocks.size(); ++i) {
            const AmrData::Block& block = amr.blocks[i];
            levels.push_back(int32_t(block.level));
            bounds.push_back({block.lower.x, block.lower.y, block.lower.z, block.upper.x, block.upper.y, block.upper.z});
            const glm::uvec3 dims(block.upper - block.lower + 1);
            ANARIArray3D values3d =
                handles_.keep(anariNewArray3D(d_, nullptr, nullptr, nullptr, ANARI_FLOAT32, dims.x, dims.y, dims.z), "array");
            std::memcpy(anariMapArray(d_, values3d), block.values.data(), block.values.size() * sizeof(float));
            anariUnmapArray(d_, values3d);
            blockArrays[i] = values3d;
        }
        anariUnmapArray(d_, data);
        setObject(d_, field, "block.data", ANARI_ARRAY1D, data);
        setObject(d_, field, "block.level", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, levels, ANARI_INT32), "array"));
        setObject(d_, field, "block.bounds", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, bounds, ANARI_INT32_BOX3), "array"));
        setObject(d_, field, "cellWidth", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, amr.cellWidth, ANARI_FLOAT32), "array"));
        set(d_, field, "origin", amr.origin);
        set(d_, field, "spacing", amr.spacing);
        anariCommitParameters(d_, field);
        fieldRanges_[field] = values;
        return field;
    }

    // Volumes placed by `transform` (an instance of their own) instead of standing in the world as given.
    void placeVolumes(const glm::mat4& transform) { volumeTransform_ = transform; }

    // The field as a transferFunction1D volume over the value range [lo, hi] with the given colours and
    // opacities (`colorMap`: the named map they are, for the panels; empty: the scene's own).
    void volume(ANARISpatialField field, const std::vector<glm::vec3>& colors, const std::vector<float>& opacities,
                float unitDistance, float lo = 0.0f, float hi = 1.0f, const std::string& colorMap = "") {
        ANARIVolume v = handles_.keep(anariNewVolume(d_, "transferFunction1D"), "volume");
        setObject(d_, v, "value", ANARI_SPATIAL_FIELD, field);
        setObject(d_, v, "color", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, colors), "array"));
        setObject(d_, v, "opacity", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, opacities), "array"));
        const float range[2] = {lo, hi};
        anariSetParameter(d_, v, "valueRange", ANARI_FLOAT32_BOX1, range);
        set(d_, v, "unitDistance", unitDistance);
        anariCommitParameters(d_, v);
        volumes_.push_back(v);
        if (edits_)
            edits_->add(EditableVolume{v, "volume " + std::to_string(edits_->volumes.size()), colors, opacities, {lo, hi},
                                       unitDistance, fieldRanges_.at(field), {}, colorMap});
    }

    // The surface where the field equals `isovalue`.
    void isosurface(ANARISpatialField field, float isovalue, ANARIMaterial material) {
        ANARIGeometry g = handles_.keep(anariNewGeometry(d_, "isosurface"), "isosurface geometry");
        setObject(d_, g, "field", ANARI_SPATIAL_FIELD, field);
        set(d_, g, "isovalue", isovalue);
        surface(g, material);
        if (edits_) edits_->add(EditableIsosurface{g, "isosurface " + std::to_string(edits_->isosurfaces.size()),
                                                   isovalue, fieldRanges_.at(field)});
    }

    // Everything in one group under one identity instance, as a glTF scene's meshes are.
    AnariWorld finish(const CameraView& camera, const glm::vec3& lo, const glm::vec3& hi) {
        ANARIGroup group = handles_.keep(anariNewGroup(d_), "group");
        if (!surfaces_.empty())  // a data-parallel rank's volume slab may stand alone
            setObject(d_, group, "surface", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, surfaces_, ANARI_SURFACE), "array"));
        if (!volumes_.empty() && !volumeTransform_)
            setObject(d_, group, "volume", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, volumes_, ANARI_VOLUME), "array"));
        anariCommitParameters(d_, group);
        const auto instanceOf = [&](ANARIGroup g, const glm::mat4& transform) {
            ANARIInstance instance = handles_.keep(anariNewInstance(d_, "transform"), "instance");
            set(d_, instance, "transform", transform);
            setObject(d_, instance, "group", ANARI_GROUP, g);
            anariCommitParameters(d_, instance);
            return instance;
        };
        std::vector<ANARIInstance> instances{instanceOf(group, glm::mat4(1.0f))};
        if (!volumes_.empty() && volumeTransform_) {
            ANARIGroup placed = handles_.keep(anariNewGroup(d_), "group");
            setObject(d_, placed, "volume", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, volumes_, ANARI_VOLUME), "array"));
            anariCommitParameters(d_, placed);
            instances.push_back(instanceOf(placed, *volumeTransform_));
        }

        AnariWorld out;
        out.world = anariNewWorld(d_);
        if (!out.world) throw std::runtime_error("the ANARI device returned no world");
        setObject(d_, out.world, "instance", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, instances, ANARI_INSTANCE), "array"));
        if (!lights_.empty())
            setObject(d_, out.world, "light", ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, lights_, ANARI_LIGHT), "array"));
        anariCommitParameters(d_, out.world);
        out.cameras.push_back(camera);
        out.boundsMin = lo;
        out.boundsMax = hi;
        return out;
    }

private:
    template <typename T>
    void attach(ANARIObject object, const char* name, const std::vector<T>& values) {
        setObject(d_, object, name, ANARI_ARRAY1D, handles_.keep(anari::newArray1D(d_, values), "array"));
    }

    void surface(ANARIGeometry g, ANARIMaterial material) {
        anariCommitParameters(d_, g);
        ANARISurface s = handles_.keep(anariNewSurface(d_), "surface");
        setObject(d_, s, "geometry", ANARI_GEOMETRY, g);
        setObject(d_, s, "material", ANARI_MATERIAL, material);
        anariCommitParameters(d_, s);
        surfaces_.push_back(s);
    }

    ANARIDevice d_;
    anari::HandleList handles_;
    std::vector<ANARISurface> surfaces_;
    std::vector<ANARIVolume> volumes_;
    std::optional<glm::mat4> volumeTransform_;
    std::vector<ANARILight> lights_;
    SceneEdits* edits_;
    std::map<ANARISpatialField, glm::vec2> fieldRanges_;  // each field's smallest and largest sample
};

CameraView lookAt(const glm::vec3& from, const glm::vec3& at, float fovyDegrees) {
    CameraView view;
    view.name = "demo";
    view.position = from;
    view.direction = glm::normalize(at - from);
    view.fovy = glm::radians(fovyDegrees);
    return view;
}

AnariWorld defaultScene(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    DemoBuilder b(d, extraLights, edits);
    b.mesh(tiledFloor(6.0f, 12, glm::vec3(0.75f, 0.74f, 0.70f), glm::vec3(0.50f, 0.52f, 0.55f)), b.matteFromColors());
    b.spheres({{-1.6f, 0.6f, 0.3f}}, 0.6f, b.matte(glm::vec3(0.75f, 0.14f, 0.11f)));                    // matte
    b.spheres({{0.0f, 0.75f, -0.5f}}, 0.75f, b.pbr(glm::vec3(1.0f, 0.78f, 0.34f), 1.0f, 0.12f));       // polished gold
    b.spheres({{1.6f, 0.55f, 0.4f}}, 0.55f, b.pbr(glm::vec3(0.12f, 0.32f, 0.80f), 0.0f, 0.45f));        // blue plastic
    for (int i = 0; i < 5; ++i)  // a row of steel balls, smooth to rough
        b.spheres({{-1.2f + 0.6f * float(i), 0.18f, 1.7f}}, 0.18f, b.pbr(glm::vec3(0.9f), 1.0f, 0.05f + 0.2f * float(i)));
    const glm::mat4 torusPlace = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.8f, 0.72f, -2.2f)),
                                             glm::radians(65.0f), glm::vec3(1.0f, 0.0f, 0.3f));
    b.mesh(torus(0.5f, 0.18f, 64, 24, torusPlace), b.pbr(glm::vec3(0.95f, 0.64f, 0.54f), 1.0f, 0.3f));  // copper
    b.cylinders({{-2.7f, 0.0f, -2.6f}, {-2.7f, 2.4f, -2.6f}, {-1.5f, 0.0f, -3.2f}, {-1.5f, 1.6f, -3.2f}}, 0.25f,
                b.matte(glm::vec3(0.85f)));
    b.directionalLight(glm::vec3(-0.5f, -1.0f, -0.35f), glm::vec3(1.0f, 0.95f, 0.85f), 2.5f);
    b.quadLight(glm::vec3(-1.5f, 3.2f, 1.5f), glm::vec3(0.0f, 0.0f, -1.5f), glm::vec3(3.0f, 0.0f, 0.0f),
                glm::vec3(0.9f, 0.95f, 1.0f), 3.0f);
    AnariWorld out = b.finish(lookAt({0.0f, 2.0f, 6.5f}, {0.0f, 0.6f, 0.0f}, 40.0f), {-6.0f, 0.0f, -6.0f}, {6.0f, 3.2f, 6.0f});
    out.ambientRadiance = 0.25f;
    out.background = glm::vec4(0.55f, 0.65f, 0.80f, 1.0f);
    return out;
}

// The room spans x, z in [-1, 1] and y in [0, 2]; its open side faces the camera at +Z.
AnariWorld cornellScene(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    DemoBuilder b(d, extraLights, edits);
    const glm::vec3 white(0.725f, 0.71f, 0.68f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
    MeshData room;
    room.quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0});   // floor, facing up
    room.quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2});   // ceiling, facing down
    room.quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0});   // back wall, facing +Z
    b.mesh(room, b.matte(white));
    MeshData left, right;
    left.quad({-1, 0, -1}, {0, 2, 0}, {0, 0, 2});   // facing +X
    right.quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0});   // facing -X
    b.mesh(left, b.matte(red));
    b.mesh(right, b.matte(green));
    MeshData boxes;
    boxes.box(glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.33f, 0.3f, 0.37f)),
                                     glm::radians(-17.0f), glm::vec3(0, 1, 0)), glm::vec3(0.6f)));
    boxes.box(glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.34f, 0.6f, -0.29f)),
                                     glm::radians(17.0f), glm::vec3(0, 1, 0)), glm::vec3(0.6f, 1.2f, 0.6f)));
    b.mesh(boxes, b.matte(white));
    b.quadLight({-0.25f, 1.98f, -0.2f}, {0.5f, 0, 0}, {0, 0, 0.4f}, glm::vec3(1.0f, 0.75f, 0.45f), 25.0f);
    return b.finish(lookAt({0.0f, 1.0f, 3.9f}, {0.0f, 1.0f, 0.0f}, 39.3f), {-1.0f, 0.0f, -1.0f}, {1.0f, 2.0f, 1.0f});
}

// The Marschner-Lobb test signal (Marschner & Lobb, "An evaluation of reconstruction filters for volume
// rendering", 1994) on [-1, 1]^3, alpha 0.25 and f_M 6: values in [0, 1], rings that show how a renderer
// reconstructs the field.
float marschnerLobb(const glm::vec3& p) {
    const float alpha = 0.25f, frequency = 6.0f, pi = glm::pi<float>();
    const float r = std::sqrt(p.x * p.x + p.y * p.y);
    const float rho = std::cos(2.0f * pi * frequency * std::cos(pi * r / 2.0f));
    return (1.0f - std::sin(pi * p.z / 2.0f) + alpha * (1.0f + rho)) / (2.0f * (1.0f + alpha));
}

// The Marschner-Lobb signal sampled on a dims^3 grid over [-1, 1]^3, its z axis turned to point up (world y).
std::vector<float> marschnerLobbSamples(glm::uvec3 dims) {
    std::vector<float> samples;
    samples.reserve(size_t(dims.x) * dims.y * dims.z);
    for (uint32_t z = 0; z < dims.z; ++z)
        for (uint32_t y = 0; y < dims.y; ++y)
            for (uint32_t x = 0; x < dims.x; ++x) {
                const glm::vec3 p = glm::vec3(x, y, z) / glm::vec3(dims - 1u) * 2.0f - 1.0f;
                samples.push_back(marschnerLobb(glm::vec3(p.x, p.z, p.y)));
            }
    return samples;
}

// Where a field stands: its samples span [lo, hi], a part (a data-parallel rank's slab) of the whole
// field's box [boxLo, boxHi] of at most 2 across standing on the floor. stage: this world holds the floor
// and the sun (under mpirun rank 0 alone does).
struct FieldPlacement {
    glm::vec3 lo, hi, boxLo, boxHi;
    bool stage = true;
    std::optional<glm::vec2> values;    // the whole field's smallest and largest sample (a slab's own: none)
};

// The floor, sun and sky the field demos and field files stand in; `makeField` makes the field and
// `addField` draws it. The camera looks at the whole box from the front and above.
template <class MakeField, class AddField>
AnariWorld fieldScene(ANARIDevice d, MakeField makeField, const FieldPlacement& at, const std::vector<ANARILight>& extraLights,
                      SceneEdits* edits, AddField addField) {
    DemoBuilder b(d, at.stage ? extraLights : std::vector<ANARILight>{}, edits);  // lights live where the stage is
    if (at.stage) b.mesh(tiledFloor(4.0f, 8, glm::vec3(0.7f), glm::vec3(0.45f)), b.matteFromColors());
    addField(b, makeField(b));
    if (at.stage) b.directionalLight(glm::vec3(-0.6f, -1.0f, -0.4f), glm::vec3(1.0f, 0.95f, 0.85f), 3.0f);
    const glm::vec3 centre = 0.5f * (at.boxLo + at.boxHi), target(centre.x, centre.y - 0.15f, centre.z);
    AnariWorld out = b.finish(lookAt(target + glm::vec3(0.0f, 1.5f, 4.6f), target, 40.0f), {-4.0f, 0.0f, -4.0f},
                              {4.0f, std::max(at.boxHi.y, 2.05f), 4.0f});
    out.ambientRadiance = 0.3f;
    out.background = glm::vec4(0.55f, 0.65f, 0.80f, 1.0f);
    return out;
}

// The Marschner-Lobb field (64^3 samples) over [-1, 1]^2 horizontally, standing just above the floor.
template <class AddField>
AnariWorld marschnerLobbScene(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits,
                              AddField addField) {
    const glm::uvec3 dims(64);
    const glm::vec3 lo(-1.0f, 0.05f, -1.0f), hi(1.0f, 2.05f, 1.0f);
    const FieldPlacement at{lo, hi, lo, hi};
    const auto makeField = [&](DemoBuilder& b) { return b.field(dims, marschnerLobbSamples(dims), at.lo, at.hi, at.values); };
    return fieldScene(d, makeField, at, extraLights, edits, addField);
}

// A Marschner-Lobb volume (64^3 samples) standing on a floor, under a sun and a sky: the medium scatters
// (albedo from a warm colour map) and casts its shadow.
AnariWorld volumeScene(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    return marschnerLobbScene(d, extraLights, edits, [](DemoBuilder& b, ANARISpatialField field) {
        b.volume(field, {{0.15f, 0.2f, 0.6f}, {0.2f, 0.7f, 0.8f}, {0.95f, 0.85f, 0.4f}, {0.95f, 0.35f, 0.15f}},
                 // A thin shell around the value 0.5, where the signal's rings are.
                 {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.8f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
                  0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
                 0.01f);
    });
}

// The same field's iso-surface at 0.5 as polished gold: the rings, traced exactly through the trilinear
// interpolant of the 64^3 samples.
AnariWorld isosurfaceScene(ANARIDevice d, const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    return marschnerLobbScene(d, extraLights, edits, [](DemoBuilder& b, ANARISpatialField field) {
        b.isosurface(field, 0.5f, b.pbr({1.0f, 0.78f, 0.34f}, 1.0f, 0.3f));
    });
}

// Colour maps as a few evenly spaced control points (the device interpolates linearly between them),
// used directly as albedo. viridis: matplotlib's viridis (van der Walt and Smith, 2015), entries 0, 64,
// 128, 192 and 255 of the 256 in matplotlib's _cm_listed.py; coolwarm: Moreland's diverging map ("Diverging Color
// Maps for Scientific Visualization", 2009), its published end points RGB (59, 76, 192) and (180, 4, 38)
// and midpoint (221, 221, 221); grayscale: black to white.
std::vector<glm::vec3> colorMap(const std::string& name) {
    if (name == "coolwarm")
        return {glm::vec3(59, 76, 192) / 255.0f, glm::vec3(221, 221, 221) / 255.0f, glm::vec3(180, 4, 38) / 255.0f};
    if (name == "grayscale") return {glm::vec3(0.0f), glm::vec3(1.0f)};
    return {{0.267004f, 0.004874f, 0.329415f},
            {0.229739f, 0.322361f, 0.545706f},
            {0.127568f, 0.566949f, 0.550556f},
            {0.369214f, 0.788888f, 0.382914f},
            {0.993248f, 0.906157f, 0.143936f}};
}

// The piecewise-linear colour map at t in [0, 1].
glm::vec3 colorAt(const std::vector<glm::vec3>& map, float t) {
    const float x = std::clamp(t, 0.0f, 1.0f) * float(map.size() - 1);
    const size_t i = std::min(size_t(x), map.size() - 2);
    return glm::mix(map[i], map[i + 1], x - float(i));
}

}  // namespace

std::vector<std::string> transferFunctionNames() { return {"viridis", "coolwarm", "grayscale"}; }

std::vector<glm::vec3> transferFunctionColors(const std::string& name) {
    checkTransferFunctionName(name);
    return colorMap(name);
}

void checkTransferFunctionName(const std::string& name) {
    const std::vector<std::string> names = transferFunctionNames();
    if (std::find(names.begin(), names.end(), name) != names.end()) return;
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown transfer function '" + name + "' (known: " + known + ")");
}

// Draws a field as `options` say: a volume through the colour map over the value range (the options', else
// `dataRange`), and an iso-surface per isovalue coloured by the map.
auto drawField(const FieldSceneOptions& options, glm::vec2 dataRange) {
    return [options, dataRange](DemoBuilder& b, ANARISpatialField field) {
        const std::vector<glm::vec3> colors = colorMap(options.transferFunction.empty() ? "viridis" : options.transferFunction);
        const glm::vec2 values = options.valueRange.value_or(dataRange);
        const float range = values.y - values.x;
        if (!options.transferFunction.empty())
            b.volume(field, colors, {0.0f, options.opacity}, options.unitDistance.value_or(kDefaultUnitDistance),
                     values.x, values.y, options.transferFunction);
        for (float isovalue : options.isovalues) {
            const float t = range > 0.0f ? (isovalue - values.x) / range : 0.5f;
            b.isosurface(field, isovalue, b.matte(colorAt(colors, t)));
        }
    };
}

AnariWorld buildFieldScene(ANARIDevice device, const VolumeData& data, const FieldSceneOptions& options,
                           const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    if (!options.transferFunction.empty()) checkTransferFunctionName(options.transferFunction);
    const glm::uvec3 whole = data.wholeDims == glm::uvec3(0) ? data.dims : data.wholeDims;
    const glm::vec3 extent = glm::vec3(whole - 1u) * data.spacing;
    const float scale = 2.0f / std::max({extent.x, extent.y, extent.z});
    const glm::vec3 boxLo(-0.5f * scale * extent.x, 0.05f, -0.5f * scale * extent.z), step = scale * data.spacing;
    FieldPlacement at{boxLo, boxLo, boxLo, boxLo + scale * extent, options.stage, glm::vec2(data.minValue, data.maxValue)};
    at.lo.z += step.z * float(data.zFirst);
    at.hi = at.lo + step * glm::vec3(data.dims - 1u);
    const auto makeField = [&](DemoBuilder& b) { return b.field(data.dims, data.values, at.lo, at.hi, at.values); };
    return fieldScene(device, makeField, at, extraLights, edits, drawField(options, glm::vec2(data.minValue, data.maxValue)));
}

namespace {

// A field in an object space of its own (box lo..hi), on the stage by an instance transform: its longest side 2,
// centred, just above the floor. `makeField` makes it with the builder.
template <class MakeField>
AnariWorld placedFieldScene(ANARIDevice device, const glm::dvec3& lo, const glm::dvec3& hi, glm::vec2 values,
                            const FieldSceneOptions& options, const std::vector<ANARILight>& extraLights, SceneEdits* edits,
                            MakeField makeField) {
    if (!options.transferFunction.empty()) checkTransferFunctionName(options.transferFunction);
    const glm::vec3 extent(hi - lo);
    const float scale = 2.0f / std::max({extent.x, extent.y, extent.z, 1e-30f});
    const glm::vec3 boxLo(-0.5f * scale * extent.x, 0.05f, -0.5f * scale * extent.z);
    const FieldPlacement at{boxLo, boxLo + scale * extent, boxLo, boxLo + scale * extent, options.stage, values};
    const glm::mat4 place = glm::translate(glm::mat4(1.0f), boxLo) * glm::scale(glm::mat4(1.0f), glm::vec3(scale)) *
                            glm::translate(glm::mat4(1.0f), -glm::vec3(lo));
    const auto make = [&](DemoBuilder& b) {
        b.placeVolumes(place);
        return makeField(b, values);
    };
    return fieldScene(device, make, at, extraLights, edits, drawField(options, values));
}

}  // namespace

AnariWorld buildNanoVdbScene(ANARIDevice device, const NanoVdbFile& grid, const FieldSceneOptions& options,
                             const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    return placedFieldScene(device, grid.worldLo, grid.worldHi, glm::vec2(grid.minValue, grid.maxValue), options, extraLights,
                            edits, [&](DemoBuilder& b, glm::vec2 values) { return b.nanovdbField(grid.grid, values); });
}

AnariWorld buildAmrScene(ANARIDevice device, const AmrPart& amr, const FieldSceneOptions& options,
                         const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    return placedFieldScene(device, amr.wholeLo, amr.wholeHi, glm::vec2(amr.blocks.minValue, amr.blocks.maxValue), options,
                            extraLights, edits, [&](DemoBuilder& b, glm::vec2 values) { return b.amrField(amr.blocks, values); });
}

AnariWorld buildMeshScene(ANARIDevice device, const MeshPart& mesh, const FieldSceneOptions& options,
                          const std::vector<ANARILight>& extraLights, SceneEdits* edits) {
    if (!options.transferFunction.empty()) checkTransferFunctionName(options.transferFunction);
    const glm::vec3 extent = mesh.wholeHi - mesh.wholeLo;
    const float scale = 2.0f / std::max({extent.x, extent.y, extent.z});
    const glm::vec3 boxLo(-0.5f * scale * extent.x, 0.05f, -0.5f * scale * extent.z);
    const glm::vec3 offset = boxLo - mesh.wholeLo * scale;
    const FieldPlacement at{boxLo, boxLo + scale * extent, boxLo, boxLo + scale * extent, options.stage,
                            glm::vec2(mesh.cells.minValue, mesh.cells.maxValue)};
    const auto makeField = [&](DemoBuilder& b) { return b.unstructuredField(mesh.cells, scale, offset, *at.values); };
    return fieldScene(device, makeField, at, extraLights, edits, drawField(options, *at.values));
}

std::vector<std::string> demoSceneNames() { return {"default", "cornell", "volume", "isosurface"}; }

void checkDemoSceneName(const std::string& name) {
    const std::vector<std::string> names = demoSceneNames();
    if (std::find(names.begin(), names.end(), name) != names.end()) return;
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown demo scene '" + name + "' (known: " + known + ")");
}

AnariWorld buildDemoScene(ANARIDevice device, const std::string& name, const std::vector<ANARILight>& extraLights,
                          SceneEdits* edits) {
    checkDemoSceneName(name);
    if (name == "cornell") return cornellScene(device, extraLights, edits);
    if (name == "volume") return volumeScene(device, extraLights, edits);
    if (name == "isosurface") return isosurfaceScene(device, extraLights, edits);
    return defaultScene(device, extraLights, edits);
}

}  // namespace ripple::apps
