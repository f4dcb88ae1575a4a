// Deterministic generators of test geometry and rays (see SceneGenerators.h for what each one promises).
#include "tests/support/SceneGenerators.h"

#include "tests/support/ReferenceTracer.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <unordered_map>
#include <utility>

namespace ripple::test {

using glm::dvec3;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Uniform numbers built from raw mt19937 output rather than std::uniform_real_distribution, whose
// algorithm differs between standard libraries: a seed must name the same scene everywhere.
class Rng {
public:
    explicit Rng(uint32_t seed) : engine_(seed) {}

    double uniform() {  // [0, 1) with 53 random bits
        const uint64_t hi = engine_() >> 5, lo = engine_() >> 6;
        return double((hi << 26) | lo) * 0x1p-53;
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    uint32_t below(uint32_t n) { return std::min(uint32_t(uniform() * n), n - 1); }
    dvec3 inBox(const dvec3& lo, const dvec3& hi) {
        const double x = uniform(lo.x, hi.x), y = uniform(lo.y, hi.y), z = uniform(lo.z, hi.z);
        return dvec3(x, y, z);
    }
    dvec3 unitVector() {  // uniform on the sphere (Archimedes: z uniform, azimuth uniform)
        const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * kPi);
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return dvec3(s * std::cos(phi), s * std::sin(phi), z);
    }
    dvec3 inBall(double radius) {
        const double r = radius * std::cbrt(uniform());
        return r * unitVector();
    }

private:
    std::mt19937 engine_;
};

glm::vec3 toFloat(const dvec3& v) { return glm::vec3(v); }

gpu::Ray makeRay(const glm::vec3& origin, const glm::vec3& direction) {
    return gpu::Ray{glm::vec4(origin, 0.0f), glm::vec4(direction, kInfinity)};
}

// Any unit vector perpendicular to the unit vector n.
dvec3 perpendicular(const dvec3& n) {
    const dvec3 helper = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    return glm::normalize(glm::cross(n, helper));
}

// The box [lo, hi] grown by `fraction` of its size on every side. A flat side counts as 1e-3 of the box's
// magnitude (at least 1e-3), so rays around a plane or a single point still start off it.
void enlarge(dvec3& lo, dvec3& hi, double fraction) {
    const double magnitude = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                                       std::abs(hi.y), std::abs(hi.z), 1.0});
    const dvec3 size = glm::max(hi - lo, dvec3(1e-3 * magnitude));
    lo -= fraction * size;
    hi += fraction * size;
}

// Appends a triangle as three new vertices, in a random rotation of its vertex order so tests do not
// depend on which vertex carries the degeneracy.
void addTriangle(core::TriangleMesh& mesh, Rng& rng, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    const uint32_t r = rng.below(3);
    glm::uvec3 idx(base + r, base + (r + 1) % 3, base + (r + 2) % 3);
    mesh.indices.push_back(idx);
}

uint64_t edgeKey(uint32_t a, uint32_t b) {
    return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

glm::mat4 randomAffine(Rng& rng, double spread) {
    // Shoemake's uniform random rotation.
    const double u1 = rng.uniform(), u2 = rng.uniform(0.0, 2.0 * kPi), u3 = rng.uniform(0.0, 2.0 * kPi);
    const double s1 = std::sqrt(1.0 - u1), s2 = std::sqrt(u1);
    const glm::dquat q(s2 * std::cos(u3), s1 * std::sin(u2), s1 * std::cos(u2), s2 * std::sin(u3));
    const glm::dmat3 rotation = glm::mat3_cast(q);
    const double sx = rng.uniform(0.5, 2.0), sy = rng.uniform(0.5, 2.0), sz = rng.uniform(0.5, 2.0);
    const glm::dmat3 linear = rotation * glm::dmat3(sx, 0, 0, 0, sy, 0, 0, 0, sz);
    const dvec3 translation = rng.inBox(dvec3(-spread), dvec3(spread));
    glm::mat4 m{glm::mat3(linear)};
    m[3] = glm::vec4(toFloat(translation), 1.0f);
    return m;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
// Scenes

core::SceneDescription sceneOf(core::TriangleMesh mesh) {
    core::SceneDescription scene;
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f)});
    return scene;
}

core::SceneDescription sceneOf(core::SphereSet spheres) {
    core::SceneDescription scene;
    scene.sphereSets.push_back(std::move(spheres));
    scene.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)});
    return scene;
}

core::SceneDescription sceneOf(core::CylinderSet cylinders) {
    core::SceneDescription scene;
    scene.cylinderSets.push_back(std::move(cylinders));
    scene.instances.push_back({{core::GeometryKind::Cylinders, 0}, glm::mat4(1.0f)});
    return scene;
}

bvh::Aabb worldBounds(const core::SceneDescription& scene) {
    std::vector<bvh::Aabb> meshBounds(scene.meshes.size()), sphereBounds(scene.sphereSets.size()),
        cylinderBounds(scene.cylinderSets.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const core::TriangleMesh& mesh = scene.meshes[m];
        for (uint32_t t = 0; t < triangleCount(mesh); ++t) {
            if (!isTriangleValid(mesh, t)) continue;
            const glm::uvec3 idx = triangleIndices(mesh, t);
            for (int k = 0; k < 3; ++k) meshBounds[m].extend(mesh.positions[idx[k]]);
        }
    }
    for (size_t s = 0; s < scene.sphereSets.size(); ++s) {
        const core::SphereSet& set = scene.sphereSets[s];
        for (uint32_t i = 0; i < sphereCount(set); ++i) {
            if (!isSphereValid(set, i)) continue;
            const float r = sphereRadius(set, i);
            sphereBounds[s].extend(set.centers[i] - glm::vec3(r));
            sphereBounds[s].extend(set.centers[i] + glm::vec3(r));
        }
    }
    for (size_t s = 0; s < scene.cylinderSets.size(); ++s) {
        const core::CylinderSet& set = scene.cylinderSets[s];
        for (uint32_t i = 0; i < cylinderCount(set); ++i) {
            if (!isCylinderValid(set, i)) continue;
            const glm::uvec2 idx = cylinderIndices(set, i);
            const float r = cylinderRadius(set, i);
            for (int k = 0; k < 2; ++k) {
                cylinderBounds[s].extend(set.positions[idx[k]] - glm::vec3(r));
                cylinderBounds[s].extend(set.positions[idx[k]] + glm::vec3(r));
            }
        }
    }
    bvh::Aabb world;
    for (const core::InstanceDescription& inst : scene.instances) {
        if (!isTransformValid(inst.transform)) continue;
        const core::GeometryRef& g = inst.geometry;
        const bvh::Aabb* local = nullptr;
        if (g.kind == core::GeometryKind::Triangles && g.index < meshBounds.size()) local = &meshBounds[g.index];
        if (g.kind == core::GeometryKind::Spheres && g.index < sphereBounds.size()) local = &sphereBounds[g.index];
        if (g.kind == core::GeometryKind::Cylinders && g.index < cylinderBounds.size()) local = &cylinderBounds[g.index];
        if (local == nullptr || local->empty()) continue;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? local->hi.x : local->lo.x, (corner & 2) ? local->hi.y : local->lo.y,
                              (corner & 4) ? local->hi.z : local->lo.z);
            world.extend(glm::vec3(inst.transform * glm::vec4(p, 1.0f)));
        }
    }
    return world;
}

core::TriangleMesh randomTriangleSoup(uint32_t count, uint32_t seed, float extent) {
    Rng rng(seed);
    core::TriangleMesh mesh;
    mesh.positions.reserve(3 * size_t(count));
    const double half = std::min(double(extent), double(extent) / std::cbrt(std::max(count, 1u)));
    const dvec3 centerLo(-extent + half), centerHi(extent - half);
    for (uint32_t i = 0; i < count; ++i) {
        const dvec3 center = rng.inBox(centerLo, centerHi);
        for (int k = 0; k < 3; ++k) mesh.positions.push_back(toFloat(center + rng.inBox(dvec3(-half), dvec3(half))));
    }
    return mesh;
}

core::TriangleMesh degenerateAndNeedleMesh(uint32_t seed) {
    using L = DegenerateMeshLayout;
    Rng rng(seed);
    core::TriangleMesh mesh;
    const auto anywhere = [&] { return rng.inBox(dvec3(-0.8), dvec3(0.8)); };
    // Keeps drawing until the triangle has nonzero area in double: float rounding of a needle's short
    // edge can, rarely, collapse it.
    const auto addValid = [&](auto make) {
        for (;;) {
            const auto [a, b, c] = make();
            core::TriangleMesh probe{{toFloat(a), toFloat(b), toFloat(c)}, {}};
            if (!isTriangleValid(probe, 0)) continue;
            addTriangle(mesh, rng, probe.positions[0], probe.positions[1], probe.positions[2]);
            return;
        }
    };

    for (uint32_t i = 0; i < L::normal; ++i)
        addValid([&] {
            const dvec3 p = anywhere();
            return std::array{p + rng.inBall(0.15), p + rng.inBall(0.15), p + rng.inBall(0.15)};
        });
    for (uint32_t i = 0; i < L::needles; ++i)
        addValid([&] {
            const dvec3 apex = anywhere(), dir = rng.unitVector();
            const double length = rng.uniform(0.1, 0.2);
            const dvec3 b = apex + length * dir;
            return std::array{apex, b, b + 1e-6 * length * perpendicular(dir)};
        });
    for (uint32_t i = 0; i < L::coincident; ++i) {
        const glm::vec3 p = toFloat(anywhere()), q = toFloat(anywhere() * 0.2 + dvec3(p) * 0.8);
        if (i % 2 == 0) {  // the same vertex referenced twice
            const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
            mesh.positions.insert(mesh.positions.end(), {p, q});
            mesh.indices.push_back(glm::uvec3(base, base, base + 1));
        } else {           // two distinct vertices with equal positions
            addTriangle(mesh, rng, p, p, q);
        }
    }
    for (uint32_t i = 0; i < L::collinear; ++i) {
        // Exactly collinear after rounding to float: either only one coordinate varies, or the points are
        // small multiples of 1/8 along an integer direction, which float and double represent exactly.
        if (i % 2 == 0) {
            const glm::vec3 p = toFloat(anywhere());
            const int axis = int(rng.below(3));
            glm::vec3 b = p, c = p;
            b[axis] += float(rng.uniform(0.05, 0.2));
            c[axis] -= float(rng.uniform(0.05, 0.2));
            addTriangle(mesh, rng, p, b, c);
        } else {
            const glm::vec3 p(float(int(rng.below(9)) - 4) / 8.0f, float(int(rng.below(9)) - 4) / 8.0f,
                              float(int(rng.below(9)) - 4) / 8.0f);
            const glm::vec3 dir(float(1 + rng.below(3)), -float(1 + rng.below(3)), float(rng.below(3)));
            addTriangle(mesh, rng, p, p + dir / 8.0f, p + dir * (3.0f / 8.0f));
        }
    }
    for (uint32_t i = 0; i < L::slivers; ++i)
        addValid([&] {
            const dvec3 a = anywhere(), dir = rng.unitVector();
            const double length = rng.uniform(0.1, 0.3);
            const dvec3 b = a + length * dir;
            const dvec3 mid = a + rng.uniform(0.2, 0.8) * length * dir;
            return std::array{a, b, mid + 1e-4 * length * perpendicular(dir)};
        });
    return mesh;
}

core::SphereSet randomSpheres(uint32_t count, uint32_t seed, float extent, float minRadius, float maxRadius) {
    Rng rng(seed);
    core::SphereSet set;
    set.centers.reserve(count);
    set.radii.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        set.centers.push_back(toFloat(rng.inBox(dvec3(-extent), dvec3(extent))));
        set.radii.push_back(float(rng.uniform(minRadius, maxRadius)));
    }
    return set;
}

core::TriangleMesh perturbedSphereMesh(uint32_t subdivisions, uint32_t seed, float perturbation) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<dvec3> unit = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                               {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (dvec3& p : unit) p = glm::normalize(p);
    std::vector<glm::uvec3> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (uint32_t level = 0; level < subdivisions; ++level) {
        // One new vertex per edge, found again through the map by the second triangle on that edge: the
        // sharing that makes the mesh watertight.
        std::unordered_map<uint64_t, uint32_t> midpoints;
        midpoints.reserve(faces.size() * 2);
        const auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto [it, inserted] = midpoints.try_emplace(edgeKey(a, b), static_cast<uint32_t>(unit.size()));
            if (inserted) unit.push_back(glm::normalize(unit[a] + unit[b]));
            return it->second;
        };
        std::vector<glm::uvec3> finer;
        finer.reserve(faces.size() * 4);
        for (const glm::uvec3& f : faces) {
            const uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
            finer.insert(finer.end(), {{f.x, ab, ca}, {ab, f.y, bc}, {ca, bc, f.z}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    Rng rng(seed);
    core::TriangleMesh mesh;
    mesh.positions.reserve(unit.size());
    for (const dvec3& p : unit) mesh.positions.push_back(toFloat(p * rng.uniform(1.0 - perturbation, 1.0 + perturbation)));
    mesh.indices = std::move(faces);
    return mesh;
}

bool isClosedManifold(const core::TriangleMesh& mesh) {
    const uint32_t count = triangleCount(mesh);
    if (count == 0) return false;
    // Directed edges (from, to) sorted by their undirected key: a closed, oriented surface has each key
    // exactly twice, once in each direction.
    std::vector<std::pair<uint64_t, uint32_t>> edges;  // (undirected key, from-vertex)
    edges.reserve(3 * size_t(count));
    for (uint32_t t = 0; t < count; ++t) {
        const glm::uvec3 idx = triangleIndices(mesh, t);
        for (int k = 0; k < 3; ++k) {
            const uint32_t from = idx[k], to = idx[(k + 1) % 3];
            if (from >= mesh.positions.size() || from == to) return false;
            edges.emplace_back(edgeKey(from, to), from);
        }
    }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size(); i += 2) {
        if (i + 1 >= edges.size() || edges[i].first != edges[i + 1].first) return false;
        if (edges[i].second == edges[i + 1].second) return false;             // same direction twice
        if (i + 2 < edges.size() && edges[i + 2].first == edges[i].first) return false;  // a third use
    }
    return true;
}

core::TriangleMesh gridMesh(uint32_t trianglesAtLeast, float size, float amplitude) {
    uint64_t n = std::max<uint64_t>(1, uint64_t(std::ceil(std::sqrt(double(trianglesAtLeast) / 2.0))));
    while (2 * n * n < trianglesAtLeast) ++n;
    const uint32_t cells = static_cast<uint32_t>(n), side = cells + 1;
    core::TriangleMesh mesh;
    mesh.positions.resize(size_t(side) * side);
    mesh.indices.resize(2 * size_t(cells) * cells);
    const double step = double(size) / cells, frequency = 2.0 * kPi * 3.0 / size;
    for (uint32_t j = 0; j < side; ++j) {
        const double z = -0.5 * size + j * step;
        for (uint32_t i = 0; i < side; ++i) {
            const double x = -0.5 * size + i * step;
            const double y = amplitude * std::sin(frequency * x) * std::cos(frequency * z);
            mesh.positions[size_t(j) * side + i] = glm::vec3(x, y, z);
        }
    }
    for (uint32_t j = 0; j < cells; ++j) {
        for (uint32_t i = 0; i < cells; ++i) {
            const uint32_t v00 = j * side + i, v10 = v00 + 1, v01 = v00 + side, v11 = v01 + 1;
            const size_t t = 2 * (size_t(j) * cells + i);
            mesh.indices[t] = glm::uvec3(v00, v01, v11);  // counter-clockwise seen from +y
            mesh.indices[t + 1] = glm::uvec3(v00, v11, v10);
        }
    }
    return mesh;
}

core::CylinderSet randomCylinders(uint32_t count, uint32_t seed, bool caps, float extent, float minRadius,
                                  float maxRadius, float minLength, float maxLength) {
    Rng rng(seed);
    core::CylinderSet set;
    set.caps = caps ? core::CapEnds::Both : core::CapEnds::None;
    for (uint32_t i = 0; i < count; ++i) {
        const dvec3 center = rng.inBox(dvec3(-extent), dvec3(extent));
        const dvec3 halfAxis = 0.5 * rng.uniform(minLength, maxLength) * rng.unitVector();
        set.positions.push_back(toFloat(center - halfAxis));
        set.positions.push_back(toFloat(center + halfAxis));
        set.radii.push_back(float(rng.uniform(minRadius, maxRadius)));
    }
    return set;
}

core::SceneDescription instancedCopies(const core::SceneDescription& base, uint32_t copies, uint32_t seed, float spread) {
    Rng rng(seed);
    core::SceneDescription scene;
    scene.meshes = base.meshes;
    scene.sphereSets = base.sphereSets;
    scene.cylinderSets = base.cylinderSets;
    std::vector<core::InstanceDescription> originals = base.instances;
    if (originals.empty()) {
        for (uint32_t m = 0; m < base.meshes.size(); ++m)
            originals.push_back({{core::GeometryKind::Triangles, m}, glm::mat4(1.0f)});
        for (uint32_t s = 0; s < base.sphereSets.size(); ++s)
            originals.push_back({{core::GeometryKind::Spheres, s}, glm::mat4(1.0f)});
        for (uint32_t c = 0; c < base.cylinderSets.size(); ++c)
            originals.push_back({{core::GeometryKind::Cylinders, c}, glm::mat4(1.0f)});
    }
    scene.instances.reserve(size_t(copies) * originals.size());
    for (uint32_t k = 0; k < copies; ++k)
        for (const core::InstanceDescription& original : originals)
            scene.instances.push_back({original.geometry, randomAffine(rng, spread) * original.transform});
    return scene;
}

core::SceneDescription offset(const core::SceneDescription& scene, const glm::vec3& delta) {
    core::SceneDescription moved = scene;
    for (core::TriangleMesh& mesh : moved.meshes)
        for (glm::vec3& p : mesh.positions) p += delta;
    for (core::SphereSet& set : moved.sphereSets)
        for (glm::vec3& c : set.centers) c += delta;
    for (core::CylinderSet& set : moved.cylinderSets)
        for (glm::vec3& p : set.positions) p += delta;
    return moved;
}

core::SceneDescription offsetInstances(const core::SceneDescription& scene, const glm::vec3& delta) {
    core::SceneDescription moved = scene;
    glm::mat4 translation(1.0f);
    translation[3] = glm::vec4(delta, 1.0f);
    for (core::InstanceDescription& inst : moved.instances) inst.transform = translation * inst.transform;
    return moved;
}

// ---------------------------------------------------------------------------------------------------
// Rays

std::vector<gpu::Ray> randomRays(uint32_t count, uint32_t seed, const glm::vec3& lo, const glm::vec3& hi) {
    Rng rng(seed);
    dvec3 boxLo(lo), boxHi(hi);
    enlarge(boxLo, boxHi, 0.25);
    std::vector<gpu::Ray> rays;
    rays.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const dvec3 origin = rng.inBox(boxLo, boxHi);
        rays.push_back(makeRay(toFloat(origin), toFloat(rng.unitVector())));
    }
    return rays;
}

std::vector<gpu::Ray> raysTowardPoints(const core::SceneDescription& scene, uint32_t count, uint32_t seed,
                                       bool normalised) {
    // Valid primitives per geometry, gathered once; instances are sampled uniformly, then primitives.
    std::vector<std::vector<uint32_t>> meshPrims(scene.meshes.size()), spherePrims(scene.sphereSets.size()),
        cylinderPrims(scene.cylinderSets.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (uint32_t t = 0; t < triangleCount(scene.meshes[m]); ++t)
            if (isTriangleValid(scene.meshes[m], t)) meshPrims[m].push_back(t);
    for (size_t s = 0; s < scene.sphereSets.size(); ++s)
        for (uint32_t i = 0; i < sphereCount(scene.sphereSets[s]); ++i)
            if (isSphereValid(scene.sphereSets[s], i)) spherePrims[s].push_back(i);
    for (size_t c = 0; c < scene.cylinderSets.size(); ++c)
        for (uint32_t i = 0; i < cylinderCount(scene.cylinderSets[c]); ++i)
            if (isCylinderValid(scene.cylinderSets[c], i)) cylinderPrims[c].push_back(i);
    std::vector<uint32_t> instances;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const core::InstanceDescription& inst = scene.instances[i];
        const core::GeometryRef& g = inst.geometry;
        const bool nonEmpty =
            (g.kind == core::GeometryKind::Triangles && g.index < meshPrims.size() && !meshPrims[g.index].empty()) ||
            (g.kind == core::GeometryKind::Spheres && g.index < spherePrims.size() && !spherePrims[g.index].empty()) ||
            (g.kind == core::GeometryKind::Cylinders && g.index < cylinderPrims.size() && !cylinderPrims[g.index].empty());
        if (nonEmpty && isTransformValid(inst.transform)) instances.push_back(i);
    }
    std::vector<gpu::Ray> rays;
    if (instances.empty()) return rays;

    const bvh::Aabb bounds = worldBounds(scene);
    dvec3 boxLo(bounds.lo), boxHi(bounds.hi);
    enlarge(boxLo, boxHi, 0.5);
    Rng rng(seed);
    rays.reserve(count);
    while (rays.size() < count) {
        const core::InstanceDescription& inst = scene.instances[instances[rng.below(uint32_t(instances.size()))]];
        const core::GeometryRef& g = inst.geometry;
        dvec3 local;
        if (g.kind == core::GeometryKind::Triangles) {
            const core::TriangleMesh& mesh = scene.meshes[g.index];
            const std::vector<uint32_t>& prims = meshPrims[g.index];
            const glm::uvec3 idx = triangleIndices(mesh, prims[rng.below(uint32_t(prims.size()))]);
            // Uniform point in the triangle; kept off the edges so the target is unambiguous.
            const double su = std::sqrt(rng.uniform(0.01, 0.99)), w = rng.uniform(0.01, 0.99);
            local = (1.0 - su) * dvec3(mesh.positions[idx.x]) + su * (1.0 - w) * dvec3(mesh.positions[idx.y]) +
                    su * w * dvec3(mesh.positions[idx.z]);
        } else if (g.kind == core::GeometryKind::Spheres) {
            const core::SphereSet& set = scene.sphereSets[g.index];
            const std::vector<uint32_t>& prims = spherePrims[g.index];
            const uint32_t s = prims[rng.below(uint32_t(prims.size()))];
            local = dvec3(set.centers[s]) + double(sphereRadius(set, s)) * rng.unitVector();
        } else {
            // A point on the side, or (a quarter of the time, when there are caps) on a cap disk.
            const core::CylinderSet& set = scene.cylinderSets[g.index];
            const std::vector<uint32_t>& prims = cylinderPrims[g.index];
            const uint32_t c = prims[rng.below(uint32_t(prims.size()))];
            const glm::uvec2 idx = cylinderIndices(set, c);
            const dvec3 a(set.positions[idx.x]), b(set.positions[idx.y]);
            const dvec3 w = glm::normalize(b - a);
            dvec3 across = rng.unitVector();
            across = glm::normalize(across - glm::dot(across, w) * w);
            const double r = cylinderRadius(set, c);
            if (set.caps != core::CapEnds::None && rng.uniform() < 0.25)
                local = (rng.uniform() < 0.5 ? a : b) + r * std::sqrt(rng.uniform(0.0, 0.98)) * across;
            else
                local = a + rng.uniform(0.01, 0.99) * (b - a) + r * across;
        }
        const glm::dmat4 transform(inst.transform);
        const dvec3 target = dvec3(transform * glm::dvec4(local, 1.0));
        // The origin is rounded to float first so that the direction aims from where the ray really starts.
        const dvec3 origin = dvec3(toFloat(rng.inBox(boxLo, boxHi)));
        dvec3 direction = target - origin;
        const double length = glm::length(direction);
        if (!(length > 0.0)) continue;
        if (normalised) direction /= length;
        rays.push_back(makeRay(toFloat(origin), toFloat(direction)));
    }
    return rays;
}

std::vector<gpu::Ray> raysFromInside(const glm::vec3& center, uint32_t count, uint32_t seed, float jitter) {
    Rng rng(seed);
    std::vector<gpu::Ray> rays;
    rays.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const dvec3 origin = dvec3(center) + (jitter > 0.0f ? rng.inBall(jitter) : dvec3(0.0));
        rays.push_back(makeRay(toFloat(origin), toFloat(rng.unitVector())));
    }
    return rays;
}

std::vector<gpu::Ray> offsetRays(std::span<const gpu::Ray> rays, const glm::vec3& delta) {
    std::vector<gpu::Ray> moved(rays.begin(), rays.end());
    for (gpu::Ray& ray : moved) ray.origin += glm::vec4(delta, 0.0f);
    return moved;
}

}  // namespace ripple::test
