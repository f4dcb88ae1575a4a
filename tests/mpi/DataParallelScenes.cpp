// Data-parallel test scenes (see DataParallelScenes.h). Every geometry is its own mesh or set with its
// transform baked in, so a rank's scene memory holds only its own primitives.
#include "tests/mpi/DataParallelScenes.h"

#include "tests/support/SceneGenerators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace ripple::test {

namespace {

uint32_t lcg(uint32_t& state) {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
}

float unit(uint32_t& state) { return float(lcg(state) & 0xFFFFu) / 65535.0f; }

core::TriangleMesh box(const glm::vec3& lo, const glm::vec3& hi) {
    core::TriangleMesh mesh;
    for (int corner = 0; corner < 8; ++corner)
        mesh.positions.push_back({corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z});
    mesh.indices = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return mesh;
}

core::TriangleMesh floorQuad(float side, float z) {
    core::TriangleMesh mesh;
    const float h = 0.5f * side;
    mesh.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
    mesh.indices = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

void add(core::SceneDescription& scene, core::TriangleMesh mesh, const core::Material& material) {
    scene.meshes.push_back(std::move(mesh));
    scene.materials.push_back(material);
    core::InstanceDescription instance;
    instance.geometry = {core::GeometryKind::Triangles, uint32_t(scene.meshes.size() - 1)};
    instance.materialIndex = uint32_t(scene.materials.size() - 1);
    scene.instances.push_back(instance);
}

core::Material matte(const glm::vec3& color) {
    core::Material m;
    m.baseColor = color;
    return m;
}

core::Camera perspective(const glm::vec3& from, const glm::vec3& at) {
    core::Camera camera;
    camera.position = from;
    camera.direction = at - from;
    camera.up = {0.0f, 0.0f, 1.0f};
    camera.fovy = 0.8f;
    return camera;
}

}  // namespace

core::SceneDescription boxesPart(uint32_t rank, uint32_t ranks) {
    constexpr uint32_t kBoxes = 64;
    std::array<uint32_t, kBoxes> order{};
    std::iota(order.begin(), order.end(), 0u);
    uint32_t state = 12345u;
    for (uint32_t i = kBoxes - 1; i > 0; --i) std::swap(order[i], order[lcg(state) % (i + 1)]);

    core::SceneDescription scene;
    for (uint32_t i = 0; i < kBoxes; ++i) {
        uint32_t boxState = 777u + i * 31u;  // the box's own stream, whoever owns it
        const glm::vec3 cell(float(i % 4) - 1.5f, float((i / 4) % 4) - 1.5f, float(i / 16) + 0.5f);
        const glm::vec3 center = cell * 1.5f + glm::vec3(0.3f * unit(boxState), 0.3f * unit(boxState), 0.0f);
        const glm::vec3 half = glm::vec3(0.3f) + 0.25f * glm::vec3(unit(boxState), unit(boxState), unit(boxState));
        core::Material material = matte(glm::vec3(0.2f) + 0.7f * glm::vec3(unit(boxState), unit(boxState), unit(boxState)));
        if (i % 9 == 4) {  // a few glossy metals, so reflections cross ranks too
            material.kind = core::Material::Kind::PhysicallyBased;
            material.metallic = 1.0f;
            material.roughness = 0.3f;
        }
        if (order[i] % ranks == rank) add(scene, box(center - half, center + half), material);
    }
    if (rank == ranks - 1) add(scene, floorQuad(60.0f, -0.4f), matte(glm::vec3(0.6f)));
    if (rank == 0) {
        core::Light point;
        point.kind = core::Light::Kind::Point;
        point.position = {2.0f, -3.0f, 9.0f};
        point.intensity = 60.0f;
        scene.lights.push_back(point);
        core::Light sun;
        sun.kind = core::Light::Kind::Directional;
        sun.direction = glm::normalize(glm::vec3(-0.5f, 0.7f, -1.0f));
        sun.intensity = 1.5f;
        sun.color = {1.0f, 0.9f, 0.7f};
        scene.lights.push_back(sun);
    }
    return scene;
}

core::Camera boxesCamera() { return perspective({9.0f, -11.0f, 9.0f}, {0.0f, 0.0f, 2.5f}); }

namespace {

// This rank's slab of the blob field: its samples (x fastest), dims and origin; empty when it has no cell.
struct FieldSlab {
    glm::uvec3 dims{0};
    std::vector<float> values;
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{0.0f};
};

FieldSlab blobSlab(uint32_t rank, uint32_t ranks) {
    constexpr uint32_t n = 33;  // samples per axis; the slabs split the 32 cells along x
    const glm::vec3 lo(-2.0f, -2.0f, 0.0f), spacing(4.0f / float(n - 1));
    auto density = [&](uint32_t x, uint32_t y, uint32_t z) {
        const glm::vec3 p = lo + glm::vec3(x, y, z) * spacing - glm::vec3(0.0f, 0.0f, 2.0f);
        return std::max(0.0f, 1.0f - glm::dot(p, p) / 4.0f) * (0.6f + 0.4f * std::sin(3.0f * p.x) * std::cos(2.0f * p.y));
    };
    const uint32_t firstCell = 32 * rank / ranks, lastCell = 32 * (rank + 1) / ranks;
    FieldSlab slab;
    if (lastCell <= firstCell) return slab;
    slab.dims = {lastCell - firstCell + 1, n, n};
    for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = firstCell; x <= lastCell; ++x) slab.values.push_back(density(x, y, z));
    slab.origin = lo + glm::vec3(float(firstCell) * spacing.x, 0.0f, 0.0f);
    slab.spacing = spacing;
    return slab;
}

// The boxes on rank 0, the floor on the last rank and the sun around the blob of volumePart and
// isosurfacePart.
void addBlobSurroundings(core::SceneDescription& scene, uint32_t rank, uint32_t ranks) {
    if (rank == 0) {
        add(scene, box({-3.5f, -1.0f, 0.0f}, {-2.5f, 0.0f, 1.5f}), matte(glm::vec3(0.8f, 0.3f, 0.2f)));
        add(scene, box({2.6f, 0.5f, 0.0f}, {3.4f, 1.5f, 2.5f}), matte(glm::vec3(0.2f, 0.5f, 0.8f)));
        core::Light sun;
        sun.kind = core::Light::Kind::Directional;
        sun.direction = glm::normalize(glm::vec3(-0.4f, 0.3f, -1.0f));
        sun.intensity = 2.0f;
        scene.lights.push_back(sun);
    }
    if (rank == ranks - 1) add(scene, floorQuad(12.0f, 0.0f), matte(glm::vec3(0.6f)));
}

}  // namespace

core::SceneDescription isosurfacePart(uint32_t rank, uint32_t ranks) {
    core::SceneDescription scene;
    FieldSlab slab = blobSlab(rank, ranks);
    if (!slab.values.empty()) {
        core::IsosurfaceSet iso;
        iso.dims = slab.dims;
        iso.values = std::move(slab.values);
        iso.origin = slab.origin;
        iso.spacing = slab.spacing;
        iso.isovalues = {0.25f, 0.6f};
        iso.colors = {{0.9f, 0.6f, 0.3f, 1.0f}, {0.3f, 0.8f, 0.5f, 1.0f}};
        scene.isosurfaceSets.push_back(std::move(iso));
        core::Material material = matte(glm::vec3(1.0f));
        material.baseColorFromVertexColor = true;
        scene.materials.push_back(material);
        core::InstanceDescription instance;
        instance.geometry = {core::GeometryKind::Isosurfaces, 0};
        instance.materialIndex = uint32_t(scene.materials.size() - 1);
        scene.instances.push_back(instance);
    }
    addBlobSurroundings(scene, rank, ranks);
    return scene;
}

core::SceneDescription volumePart(uint32_t rank, uint32_t ranks) {
    core::SceneDescription scene;
    FieldSlab slab = blobSlab(rank, ranks);
    if (!slab.values.empty()) {
        core::Volume v;
        v.dims = slab.dims;
        v.values = std::make_shared<const std::vector<float>>(std::move(slab.values));
        v.origin = slab.origin;
        v.spacing = slab.spacing;
        v.colors = {{0.9f, 0.6f, 0.3f}, {0.8f, 0.85f, 0.9f}};
        v.opacities = {0.0f, 0.9f};
        v.unitDistance = 0.5f;
        scene.volumes.push_back(std::move(v));
    }
    addBlobSurroundings(scene, rank, ranks);
    return scene;
}

core::Camera volumeCamera() { return perspective({0.0f, -9.0f, 4.0f}, {0.0f, 0.0f, 1.8f}); }

core::SceneDescription mixedPart(uint32_t rank, uint32_t ranks) {
    core::SceneDescription scene;
    uint32_t next = 0;  // instances in the order the whole scene lists them, dealt round robin
    auto mine = [&] { return next++ % ranks == rank; };

    core::Material metal = matte(glm::vec3(0.9f, 0.7f, 0.4f));
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.metallic = 1.0f;
    metal.roughness = 0.2f;
    core::Material glassy = matte(glm::vec3(0.3f, 0.6f, 0.9f));
    glassy.opacity = 0.5f;

    for (uint32_t i = 0; i < 4; ++i) {
        core::TriangleMesh sphere = perturbedSphereMesh(2, 10 + i, 0.05f);
        for (glm::vec3& p : sphere.positions) p = p * 0.8f + glm::vec3(float(i) * 1.8f - 2.7f, 0.0f, 0.8f);
        if (mine()) add(scene, std::move(sphere), i == 1 ? metal : i == 2 ? glassy : matte(glm::vec3(0.7f, 0.3f + 0.1f * float(i), 0.3f)));
    }
    for (uint32_t set = 0; set < 3; ++set) {
        core::SphereSet spheres = randomSpheres(24, 40 + set, 1.2f, 0.08f, 0.25f);
        for (glm::vec3& c : spheres.centers) c = c + glm::vec3(float(set) * 2.0f - 2.0f, 2.5f, 1.3f);
        if (!mine()) continue;
        scene.sphereSets.push_back(std::move(spheres));
        scene.materials.push_back(matte(glm::vec3(0.3f, 0.8f - 0.2f * float(set), 0.4f)));
        core::InstanceDescription instance;
        instance.geometry = {core::GeometryKind::Spheres, uint32_t(scene.sphereSets.size() - 1)};
        instance.materialIndex = uint32_t(scene.materials.size() - 1);
        scene.instances.push_back(instance);
    }
    {
        core::CylinderSet cylinders = randomCylinders(30, 77, true, 1.5f, 0.03f, 0.08f, 0.5f, 1.2f);
        for (glm::vec3& p : cylinders.positions) p = p + glm::vec3(0.0f, -2.2f, 1.0f);
        if (mine()) {
            scene.cylinderSets.push_back(std::move(cylinders));
            scene.materials.push_back(metal);
            core::InstanceDescription instance;
            instance.geometry = {core::GeometryKind::Cylinders, uint32_t(scene.cylinderSets.size() - 1)};
            instance.materialIndex = uint32_t(scene.materials.size() - 1);
            scene.instances.push_back(instance);
        }
    }
    if (mine()) add(scene, floorQuad(40.0f, 0.0f), matte(glm::vec3(0.5f)));
    if (rank == 0) {
        core::Light quad;
        quad.kind = core::Light::Kind::Quad;
        quad.position = {-1.5f, -1.5f, 6.0f};
        quad.edge1 = {3.0f, 0.0f, 0.0f};
        quad.edge2 = {0.0f, -3.0f, 0.0f};  // cross(edge1, edge2) points down, toward the scene
        quad.intensity = 8.0f;
        scene.lights.push_back(quad);
    }
    return scene;
}

core::Camera mixedCamera() { return perspective({0.0f, -9.0f, 6.0f}, {0.0f, 0.0f, 1.0f}); }

}  // namespace ripple::test
