// Builds one rank's share of the 4x4x4 boxes (see BoxesScene.h) as ANARI triangle geometries, one
// matte or metal surface per box, all in one group and one instance.
#include "apps/ripple-boxes/BoxesScene.h"

#include "apps/scene/AnariParams.h"

#include <array>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace ripple::apps {

namespace {

constexpr uint32_t kBoxes = 64;

// A small LCG: the layout must not depend on the standard library's generators.
uint32_t nextRandom(uint32_t& state) {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
}

float unitRandom(uint32_t& state) { return float(nextRandom(state) & 0xFFFFu) / 65535.0f; }

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;

    // A parallelogram cut into n x n cells, facing along cross(edge1, edge2).
    void grid(const glm::vec3& corner, const glm::vec3& edge1, const glm::vec3& edge2, uint32_t n) {
        const auto base = uint32_t(positions.size());
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t i = 0; i <= n; ++i)
                positions.push_back(corner + edge1 * (float(i) / float(n)) + edge2 * (float(j) / float(n)));
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                indices.push_back({a, b, d});
                indices.push_back({a, d, c});
            }
    }

    // An axis-aligned box with outward-facing sides.
    void box(const glm::vec3& lo, const glm::vec3& hi, uint32_t n) {
        const glm::vec3 x(hi.x - lo.x, 0, 0), y(0, hi.y - lo.y, 0), z(0, 0, hi.z - lo.z);
        grid(lo, y, x, n);      // -Z
        grid(lo + z, x, y, n);  // +Z
        grid(lo, z, y, n);      // -X
        grid(lo + x, y, z, n);  // +X
        grid(lo, x, z, n);      // -Y
        grid(lo + y, z, x, n);  // +Y
    }
};

class Builder {
public:
    explicit Builder(ANARIDevice device) : d_(device), handles_(device) {}

    void surface(const Mesh& mesh, const glm::vec3& color, bool metal) {
        ANARIGeometry geometry = handles_.keep(anariNewGeometry(d_, "triangle"), "triangle geometry");
        ANARIArray1D positions = handles_.keep(anari::newArray1D(d_, mesh.positions), "position array");
        ANARIArray1D indices = handles_.keep(anari::newArray1D(d_, mesh.indices), "index array");
        anari::setObject(d_, geometry, "vertex.position", ANARI_ARRAY1D, positions);
        anari::setObject(d_, geometry, "primitive.index", ANARI_ARRAY1D, indices);
        anariCommitParameters(d_, geometry);

        ANARIMaterial material = nullptr;
        if (metal) {
            material = handles_.keep(anariNewMaterial(d_, "physicallyBased"), "physicallyBased material");
            anari::set(d_, material, "baseColor", color);
            anari::set(d_, material, "metallic", 1.0f);
            anari::set(d_, material, "roughness", 0.3f);
        } else {
            material = handles_.keep(anariNewMaterial(d_, "matte"), "matte material");
            anari::set(d_, material, "color", color);
        }
        anariCommitParameters(d_, material);

        ANARISurface surface = handles_.keep(anariNewSurface(d_), "surface");
        anari::setObject(d_, surface, "geometry", ANARI_GEOMETRY, geometry);
        anari::setObject(d_, surface, "material", ANARI_MATERIAL, material);
        anariCommitParameters(d_, surface);
        surfaces_.push_back(surface);
    }

    void pointLight(const glm::vec3& position, float intensity) {
        ANARILight light = handles_.keep(anariNewLight(d_, "point"), "point light");
        anari::set(d_, light, "position", position);
        anari::set(d_, light, "intensity", intensity);
        anariCommitParameters(d_, light);
        lights_.push_back(light);
    }

    void sun(const glm::vec3& direction, float irradiance, const glm::vec3& color) {
        ANARILight light = handles_.keep(anariNewLight(d_, "directional"), "directional light");
        anari::set(d_, light, "direction", direction);
        anari::set(d_, light, "irradiance", irradiance);
        anari::set(d_, light, "color", color);
        anariCommitParameters(d_, light);
        lights_.push_back(light);
    }

    ANARIWorld world() {
        ANARIWorld world = anariNewWorld(d_);
        if (!world) throw std::runtime_error("the ANARI device returned no world");
        if (!surfaces_.empty()) {  // a rank may hold nothing at all: an empty world is legal
            ANARIGroup group = handles_.keep(anariNewGroup(d_), "group");
            ANARIArray1D list = handles_.keep(anari::newArray1D(d_, surfaces_, ANARI_SURFACE), "surface array");
            anari::setObject(d_, group, "surface", ANARI_ARRAY1D, list);
            anariCommitParameters(d_, group);
            ANARIInstance instance = handles_.keep(anariNewInstance(d_, "transform"), "instance");
            anari::setObject(d_, instance, "group", ANARI_GROUP, group);
            anariCommitParameters(d_, instance);
            ANARIArray1D instances = handles_.keep(anari::newArray1D(d_, std::vector<ANARIInstance>{instance}, ANARI_INSTANCE), "instance array");
            anari::setObject(d_, world, "instance", ANARI_ARRAY1D, instances);
        }
        if (!lights_.empty()) {
            ANARIArray1D lights = handles_.keep(anari::newArray1D(d_, lights_, ANARI_LIGHT), "light array");
            anari::setObject(d_, world, "light", ANARI_ARRAY1D, lights);
        }
        anariCommitParameters(d_, world);
        return world;
    }

private:
    ANARIDevice d_;
    anari::HandleList handles_;
    std::vector<ANARISurface> surfaces_;
    std::vector<ANARILight> lights_;
};

}  // namespace

BoxesPart buildBoxesPart(ANARIDevice device, uint32_t rank, uint32_t ranks, uint32_t tessellation,
                         bool lightsOnEveryRank, BoxesPartition partition) {
    std::array<uint32_t, kBoxes> permutation{};
    std::iota(permutation.begin(), permutation.end(), 0u);
    uint32_t shuffle = 12345u;
    for (uint32_t i = kBoxes - 1; i > 0; --i) std::swap(permutation[i], permutation[nextRandom(shuffle) % (i + 1)]);

    Builder builder(device);
    BoxesPart part;
    for (uint32_t i = 0; i < kBoxes; ++i) {
        uint32_t state = 777u + i * 31u;  // each box draws from its own stream, whichever rank owns it
        const glm::vec3 cell(float(i % 4) - 1.5f, float((i / 4) % 4) - 1.5f, float(i / 16) + 0.5f);
        const glm::vec3 center = cell * 1.5f + glm::vec3(0.3f * unitRandom(state), 0.3f * unitRandom(state), 0.0f);
        const glm::vec3 half =
            glm::vec3(0.3f) + 0.25f * glm::vec3(unitRandom(state), unitRandom(state), unitRandom(state));
        const glm::vec3 color =
            glm::vec3(0.2f) + 0.7f * glm::vec3(unitRandom(state), unitRandom(state), unitRandom(state));
        const uint32_t column = (i % 4) * 4 + (i / 4) % 4;  // x-major over the 4x4 columns
        const uint32_t owner = partition == BoxesPartition::Slabs ? column * ranks / 16 : permutation[i] % ranks;
        if (owner != rank) continue;
        Mesh mesh;
        mesh.box(center - half, center + half, tessellation);
        builder.surface(mesh, color, i % 9 == 4);  // a few glossy metals: reflections cross ranks too
        ++part.boxes;
        part.triangles += mesh.indices.size();
    }
    if (partition == BoxesPartition::Random && rank == ranks - 1) {
        Mesh floor;
        floor.grid({-30.0f, -30.0f, -0.4f}, {60.0f, 0.0f, 0.0f}, {0.0f, 60.0f, 0.0f}, 1);
        builder.surface(floor, glm::vec3(0.6f), false);
        part.triangles += floor.indices.size();
    }
    if (partition == BoxesPartition::Slabs) {
        // The floor cell under each column: column edges halfway between the columns' centres (1.5 apart,
        // centred on 0), the outer cells reaching the floor's edge at +-30.
        // Each cell is a surface of its own, so the rank's world boxes stay tight.
        const float edges[] = {-30.0f, -1.5f, 0.0f, 1.5f, 30.0f};
        for (uint32_t column = 0; column < 16; ++column) {
            if (column * ranks / 16 != rank) continue;
            const uint32_t ix = column / 4, iy = column % 4;
            Mesh cell;
            cell.grid({edges[ix], edges[iy], -0.4f}, {edges[ix + 1] - edges[ix], 0.0f, 0.0f},
                      {0.0f, edges[iy + 1] - edges[iy], 0.0f}, 1);
            builder.surface(cell, glm::vec3(0.6f), false);
            part.triangles += cell.indices.size();
        }
    }
    if (rank == 0 || lightsOnEveryRank) {
        builder.pointLight({2.0f, -3.0f, 9.0f}, 60.0f);
        builder.sun(glm::normalize(glm::vec3(-0.5f, 0.7f, -1.0f)), 1.5f, {1.0f, 0.9f, 0.7f});
    }
    part.world = builder.world();
    return part;
}

}  // namespace ripple::apps
