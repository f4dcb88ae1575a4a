// Checks of the CPU reference tracer and the scene generators against analytic answers, since every GPU
// traversal test trusts them.
#include "tests/support/ReferenceTracer.h"
#include "tests/support/SceneGenerators.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

using namespace ripple;
using namespace ripple::test;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

gpu::Ray ray(glm::vec3 origin, glm::vec3 direction, float tmin = 0.0f, float tmax = kInf) {
    return gpu::Ray{glm::vec4(origin, tmin), glm::vec4(direction, tmax)};
}

// The triangle (0,0,0), (1,0,0), (0,1,0): a point (x, y, 0) inside it has barycentrics u = x, v = y.
core::TriangleMesh unitTriangle() { return core::TriangleMesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}}; }

glm::mat4 translateScale(glm::vec3 translation, glm::vec3 scale) {
    glm::mat4 m(1.0f);
    m[0][0] = scale.x;
    m[1][1] = scale.y;
    m[2][2] = scale.z;
    m[3] = glm::vec4(translation, 1.0f);
    return m;
}

// Six times the signed volume enclosed by a mesh: positive when it is closed and wound outward.
double signedVolume6(const core::TriangleMesh& mesh) {
    double volume = 0.0;
    for (const glm::uvec3& f : mesh.indices)
        volume += glm::dot(glm::dvec3(mesh.positions[f.x]),
                           glm::cross(glm::dvec3(mesh.positions[f.y]), glm::dvec3(mesh.positions[f.z])));
    return volume;
}

}  // namespace

TEST_CASE("a ray straight down onto a triangle hits at the analytic t and barycentrics") {
    const core::SceneDescription scene = sceneOf(unitTriangle());

    const RefHit hit = traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -1}));
    REQUIRE(hit.found);
    CHECK(hit.t == doctest::Approx(3.0).epsilon(1e-12));
    CHECK(hit.u == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(hit.v == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(hit.instanceId == 0);
    CHECK(hit.primId == 0);
    CHECK(hit.hitCount == 1);

    // t is in units of the direction, which is not normalised.
    CHECK(traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -2})).t == doctest::Approx(1.5).epsilon(1e-12));
    // No back-face culling: from below, up.
    CHECK(traceClosest(scene, ray({0.25f, 0.5f, -2.0f}, {0, 0, 1})).t == doctest::Approx(2.0).epsilon(1e-12));
    // Open interval (tmin, tmax): a hit exactly at either end does not count.
    CHECK_FALSE(traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -1}, 3.0f)).found);
    CHECK_FALSE(traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -1}, 0.0f, 3.0f)).found);
    CHECK(traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -1}, 2.9f, 3.1f)).found);
    // Outside the triangle (u + v > 1) and pointing away.
    CHECK_FALSE(traceClosest(scene, ray({0.6f, 0.6f, 3.0f}, {0, 0, -1})).found);
    CHECK_FALSE(traceAny(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, 1})));
    CHECK(traceAny(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, -1})));
    // Unusable rays miss rather than produce garbage.
    CHECK_FALSE(traceClosest(scene, ray({kNaN, 0.5f, 3.0f}, {0, 0, -1})).found);
    CHECK_FALSE(traceClosest(scene, ray({0.25f, 0.5f, 3.0f}, {0, 0, 0})).found);
}

TEST_CASE("a ray through a sphere center hits at distance - r from outside and at r from the center") {
    const glm::vec3 center(1.0f, 2.0f, 3.0f);
    const core::SceneDescription scene = sceneOf(core::SphereSet{{center}, {0.5f}});

    const RefHit outside = traceClosest(scene, ray(center - glm::vec3(0, 0, 10), {0, 0, 1}));
    REQUIRE(outside.found);
    CHECK(outside.t == doctest::Approx(9.5).epsilon(1e-12));
    CHECK(outside.u == 0.0);
    CHECK(outside.v == 0.0);
    CHECK(outside.hitCount == 1);

    // Diagonal, non-unit direction: |d| = 3 * sqrt(3), so t = (|offset| - r) / |d|.
    const glm::vec3 diagonal(-3.0f, -3.0f, -3.0f);
    const double expected = (std::sqrt(3.0) * 3.0 - 0.5) / (std::sqrt(3.0) * 3.0);
    CHECK(traceClosest(scene, ray(center + diagonal, -diagonal)).t == doctest::Approx(expected).epsilon(1e-12));

    const RefHit inside = traceClosest(scene, ray(center, {0, 1, 0}));
    REQUIRE(inside.found);
    CHECK(inside.t == doctest::Approx(0.5).epsilon(1e-12));
    // From inside with tmin past the near root nothing changes; with tmin past the far root it misses.
    CHECK(traceClosest(scene, ray(center - glm::vec3(0, 0, 10), {0, 0, 1}, 9.6f)).t ==
          doctest::Approx(10.5).epsilon(1e-12));
    CHECK_FALSE(traceClosest(scene, ray(center - glm::vec3(0, 0, 10), {0, 0, 1}, 10.6f)).found);
    // Passing beside it.
    CHECK_FALSE(traceClosest(scene, ray(center + glm::vec3(0.51f, 0, -10), {0, 0, 1})).found);
    // A small sphere far away: the stable discriminant still finds it.
    const core::SceneDescription far = sceneOf(core::SphereSet{{{0, 0, 1e5f}}, {1e-3f}});
    CHECK(traceClosest(far, ray({0, 0, 0}, {0, 0, 1})).t == doctest::Approx(1e5 - 1e-3).epsilon(1e-12));
}

TEST_CASE("instance transforms: scale and translation give the analytic t") {
    core::SceneDescription scene;
    scene.meshes.push_back(unitTriangle());
    scene.sphereSets.push_back(core::SphereSet{{{0, 0, 0}}, {1.0f}});
    scene.instances = {
        {{core::GeometryKind::Triangles, 0}, translateScale({100, 0, 0}, glm::vec3(1))},  // off the rays
        {{core::GeometryKind::Triangles, 0}, translateScale({0, 0, 5}, glm::vec3(2))},
        {{core::GeometryKind::Spheres, 0}, translateScale({10, 0, 0}, glm::vec3(2, 1, 1))},
    };

    // World point (0.5, 1.0, 5) is object point (0.25, 0.5, 0).
    const RefHit tri = traceClosest(scene, ray({0.5f, 1.0f, 10.0f}, {0, 0, -1}));
    REQUIRE(tri.found);
    CHECK(tri.instanceId == 1);
    CHECK(tri.t == doctest::Approx(5.0).epsilon(1e-12));
    CHECK(tri.u == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(tri.v == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(traceClosest(scene, ray({0.5f, 1.0f, 10.0f}, {0, 0, -0.5f})).t == doctest::Approx(10.0).epsilon(1e-12));
    CHECK_FALSE(traceClosest(scene, ray({2.1f, 0.1f, 10.0f}, {0, 0, -1})).found);  // past the scaled edge

    // The sphere is an ellipsoid with semi-axes (2, 1, 1) around (10, 0, 0).
    const RefHit alongX = traceClosest(scene, ray({0, 0, 0}, {1, 0, 0}));
    REQUIRE(alongX.found);
    CHECK(alongX.instanceId == 2);
    CHECK(alongX.t == doctest::Approx(8.0).epsilon(1e-12));
    CHECK(traceClosest(scene, ray({10, -10, 0}, {0, 1, 0})).t == doctest::Approx(9.0).epsilon(1e-12));
    CHECK(traceClosest(scene, ray({11.5f, -10, 0}, {0, 2, 0})).t ==
          doctest::Approx((10.0 - std::sqrt(1.0 - 0.75 * 0.75)) / 2.0).epsilon(1e-12));
}

TEST_CASE("invalid triangles, spheres and instances are skipped and never hit") {
    // Every triangle covers the ray x = y = 0.25 going down; only the deepest one (z = -4) is valid.
    core::TriangleMesh mesh;
    mesh.positions = {
        {0, 0, -4}, {1, 0, -4}, {0, 1, -4},              // 0: valid
        {0, 0, -1}, {1, 0, -1}, {kNaN, 1, -1},           // 1: NaN vertex
        {0, 0, -2}, {1, 0, -2}, {0, kInf, -2},           // 2: infinite vertex
        {0, 0, -3}, {1, 0, -3}, {2, 0, -3},              // 3: collinear: zero area
    };
    mesh.indices = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}, {0, 1, 99}, {0, 0, 1}};
    CHECK(triangleCount(mesh) == 6);
    CHECK(isTriangleValid(mesh, 0));
    for (uint32_t t = 1; t < 6; ++t) CHECK_FALSE(isTriangleValid(mesh, t));

    const RefHit hit = traceClosest(sceneOf(mesh), ray({0.25f, 0.25f, 0.0f}, {0, 0, -1}));
    REQUIRE(hit.found);
    CHECK(hit.primId == 0);
    CHECK(hit.t == doctest::Approx(4.0).epsilon(1e-12));
    CHECK(hit.hitCount == 1);

    // A zero-radius sphere right on the ray would be hit at its center if it were not skipped.
    core::SphereSet spheres;
    spheres.centers = {{0, 0, 10}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3}, {kNaN, 0, 4}, {0, 0, 5}};
    spheres.radii = {0.5f, 0.0f, -1.0f, kNaN, 0.5f, kInf};
    CHECK(isSphereValid(spheres, 0));
    for (uint32_t s = 1; s < 6; ++s) CHECK_FALSE(isSphereValid(spheres, s));
    const RefHit sphereHit = traceClosest(sceneOf(spheres), ray({0, 0, 0}, {0, 0, 1}));
    REQUIRE(sphereHit.found);
    CHECK(sphereHit.primId == 0);
    CHECK(sphereHit.t == doctest::Approx(9.5).epsilon(1e-12));
    // A single radius serves every center; any other count that is not one per center voids the set.
    CHECK(sphereRadius(core::SphereSet{{{0, 0, 0}, {1, 1, 1}}, {0.25f}}, 1) == 0.25f);
    CHECK_FALSE(isSphereValid(core::SphereSet{{{0, 0, 0}}, {}}, 0));
    const core::SphereSet miscounted{{{0, 0, 5}, {0, 0, 6}, {0, 0, 7}}, {0.5f, 0.5f}};
    for (uint32_t s = 0; s < 3; ++s) CHECK_FALSE(isSphereValid(miscounted, s));
    CHECK_FALSE(traceClosest(sceneOf(miscounted), ray({0, 0, 0}, {0, 0, 1})).found);

    // Instances: only #0 is valid, though all of them sit on the ray.
    core::SceneDescription scene;
    scene.meshes = {unitTriangle(), core::TriangleMesh{}, core::TriangleMesh{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {}}};
    glm::mat4 nanTransform(1.0f), projective(1.0f);
    nanTransform[3][2] = kNaN;
    projective[2][3] = 0.5f;
    scene.instances = {
        {{core::GeometryKind::Triangles, 0}, translateScale({0, 0, -4}, glm::vec3(1))},
        {{core::GeometryKind::Triangles, 0}, nanTransform},
        {{core::GeometryKind::Triangles, 0}, translateScale({0, 0, -1}, {1, 1, 0})},    // singular
        {{core::GeometryKind::Triangles, 0}, translateScale({0, 0, -1}, glm::vec3(1e-11f))},  // det 1e-33
        {{core::GeometryKind::Triangles, 7}, glm::mat4(1.0f)},                         // no such mesh
        {{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)},                           // no sphere sets
        {{core::GeometryKind::Triangles, 1}, glm::mat4(1.0f)},                         // empty mesh
        {{core::GeometryKind::Triangles, 2}, glm::mat4(1.0f)},                         // only invalid triangles
        {{static_cast<core::GeometryKind>(5), 0}, glm::mat4(1.0f)},                    // unknown kind
        {{core::GeometryKind::Triangles, 0}, projective},                              // not affine
    };
    CHECK(isInstanceValid(scene, scene.instances[0]));
    for (size_t i = 1; i < scene.instances.size(); ++i) CHECK_FALSE(isInstanceValid(scene, scene.instances[i]));
    const ReferenceScene reference(scene);
    CHECK(reference.validInstanceCount() == 1);
    const RefHit instanceHit = reference.traceClosest(ray({0.25f, 0.25f, 0.0f}, {0, 0, -1}));
    REQUIRE(instanceHit.found);
    CHECK(instanceHit.instanceId == 0);
    CHECK(instanceHit.t == doctest::Approx(4.0).epsilon(1e-12));
}

TEST_CASE("degenerateAndNeedleMesh keeps needles and slivers and drops zero-area triangles") {
    using L = DegenerateMeshLayout;
    const core::TriangleMesh mesh = degenerateAndNeedleMesh(7);
    REQUIRE(triangleCount(mesh) == L::total);
    uint32_t t = 0;
    const auto expectGroup = [&](uint32_t count, bool valid) {
        uint32_t matching = 0;
        for (uint32_t end = t + count; t < end; ++t) matching += isTriangleValid(mesh, t) == valid ? 1 : 0;
        CHECK(matching == count);
    };
    expectGroup(L::normal, true);
    expectGroup(L::needles, true);
    expectGroup(L::coincident, false);
    expectGroup(L::collinear, false);
    expectGroup(L::slivers, true);
    CHECK(ReferenceScene(sceneOf(mesh)).validTriangleCount() == L::kept);

    // The needles really are needles: one edge about 1e-6 of the longest.
    for (uint32_t n = L::normal; n < L::normal + L::needles; ++n) {
        const glm::uvec3 idx = triangleIndices(mesh, n);
        const glm::dvec3 a(mesh.positions[idx.x]), b(mesh.positions[idx.y]), c(mesh.positions[idx.z]);
        const double ab = glm::length(b - a), bc = glm::length(c - b), ca = glm::length(a - c);
        const double ratio = std::min({ab, bc, ca}) / std::max({ab, bc, ca});
        CHECK(ratio > 1e-7);
        CHECK(ratio < 1e-5);
    }
}

TEST_CASE("ties: a ray through a shared edge hits both triangles") {
    core::TriangleMesh quad{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
    const RefHit hit = traceClosest(sceneOf(quad), ray({0.5f, 0.5f, 1.0f}, {0, 0, -1}));
    REQUIRE(hit.found);
    CHECK(hit.hitCount == 2);
    CHECK(hit.primId == 0);  // exact ties go to the lowest primitive
    CHECK(hit.t == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("perturbedSphereMesh is a closed, outward-wound manifold") {
    for (uint32_t s = 0; s <= 4; ++s) {
        const core::TriangleMesh mesh = perturbedSphereMesh(s, 11 + s, 0.2f);
        CHECK(mesh.indices.size() == 20u << (2 * s));
        CHECK(mesh.positions.size() == 10u * (1u << (2 * s)) + 2u);  // Euler: V = F / 2 + 2
        CHECK(isClosedManifold(mesh));
        CHECK(signedVolume6(mesh) > 0.0);
        for (const glm::vec3& p : mesh.positions) {
            CHECK(glm::length(p) >= 0.8f - 1e-6f);
            CHECK(glm::length(p) <= 1.2f + 1e-6f);
        }
    }
    core::TriangleMesh open = perturbedSphereMesh(2, 3, 0.1f);
    open.indices.pop_back();
    CHECK_FALSE(isClosedManifold(open));
    core::TriangleMesh flipped = perturbedSphereMesh(2, 3, 0.1f);
    std::swap(flipped.indices[5].y, flipped.indices[5].z);
    CHECK_FALSE(isClosedManifold(flipped));
    core::TriangleMesh soup = perturbedSphereMesh(1, 3, 0.1f);
    core::TriangleMesh unindexed;
    for (const glm::uvec3& f : soup.indices)
        unindexed.positions.insert(unindexed.positions.end(), {soup.positions[f.x], soup.positions[f.y], soup.positions[f.z]});
    CHECK_FALSE(isClosedManifold(unindexed));
    CHECK_FALSE(isClosedManifold(gridMesh(100)));
}

TEST_CASE("rays from inside the perturbed sphere mesh all hit (10k rays)") {
    const float perturbation = 0.2f, jitter = 0.3f;
    const core::TriangleMesh mesh = perturbedSphereMesh(4, 5, perturbation);
    const ReferenceScene reference(sceneOf(mesh));

    const std::vector<gpu::Ray> rays = raysFromInside({0, 0, 0}, 10'000, 99, jitter);
    const std::vector<RefHit> hits = reference.traceClosest(rays);
    const std::vector<uint8_t> any = reference.traceAny(rays);
    int misses = 0, anyMisses = 0, outOfRange = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        misses += hits[i].found ? 0 : 1;
        anyMisses += any[i] ? 0 : 1;
        // Unit directions: t is a distance, bounded by the shell and the jitter.
        if (hits[i].found && (hits[i].t < 1.0 - perturbation - jitter - 1e-6 || hits[i].t > 1.0 + perturbation + jitter + 1e-6))
            ++outOfRange;
    }
    CHECK(misses == 0);
    CHECK(anyMisses == 0);
    CHECK(outOfRange == 0);

    // The hardest rays for watertightness: from the center exactly at vertices and near edge midpoints,
    // where several triangles meet.
    std::vector<gpu::Ray> hard;
    for (const glm::vec3& p : mesh.positions) hard.push_back(ray({0, 0, 0}, p));
    for (size_t f = 0; f < mesh.indices.size(); f += 7) {
        const glm::uvec3 idx = mesh.indices[f];
        hard.push_back(ray({0, 0, 0}, 0.5f * (mesh.positions[idx.x] + mesh.positions[idx.y])));
    }
    // (A test with merely antisymmetric edge functions misses one of these.)
    int hardMisses = 0;
    const std::vector<RefHit> hardHits = reference.traceClosest(hard);
    for (size_t i = 0; i < hard.size(); ++i) {
        hardMisses += hardHits[i].found ? 0 : 1;
        if (i < mesh.positions.size()) CHECK(hardHits[i].t == doctest::Approx(1.0).epsilon(1e-9));  // vertex at t = 1
    }
    CHECK(hardMisses == 0);
}

TEST_CASE("gridMesh(1'000'000) has at least a million valid triangles and matches its height field") {
    const auto start = std::chrono::steady_clock::now();
    const core::TriangleMesh grid = gridMesh(1'000'000);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    MESSAGE("gridMesh(1'000'000): " << grid.indices.size() << " triangles in " << seconds << " s");
    CHECK(triangleCount(grid) >= 1'000'000u);
    CHECK(triangleCount(grid) < 1'010'000u);
    uint32_t invalid = 0;
    for (uint32_t t = 0; t < triangleCount(grid); ++t) invalid += isTriangleValid(grid, t) ? 0 : 1;
    CHECK(invalid == 0);
    CHECK(gridMesh(1).indices.size() == 2);
    CHECK(gridMesh(7).indices.size() == 8);

    // A ray straight down onto a grid vertex hits at that vertex's height.
    const glm::vec3 vertex = grid.positions[grid.positions.size() / 3 + 17];
    const RefHit hit = traceClosest(sceneOf(grid), ray({vertex.x, 1.0f, vertex.z}, {0, -1, 0}));
    REQUIRE(hit.found);
    CHECK(hit.t == doctest::Approx(1.0 - double(vertex.y)).epsilon(1e-9));
    CHECK(hit.hitCount >= 2);  // a vertex is shared by up to six triangles
}

TEST_CASE("random scenes: generators are deterministic and rays aimed at the scene hit") {
    const core::TriangleMesh soup = randomTriangleSoup(2000, 1, 2.0f);
    CHECK(soup.positions.size() == 6000);
    CHECK(soup.positions == randomTriangleSoup(2000, 1, 2.0f).positions);
    CHECK(soup.positions != randomTriangleSoup(2000, 2, 2.0f).positions);
    for (const glm::vec3& p : soup.positions) {
        CHECK(glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(2.0f))));
    }

    const core::SceneDescription soupScene = sceneOf(soup);
    const std::vector<gpu::Ray> aimed = raysTowardPoints(soupScene, 2000, 3, false);
    REQUIRE(aimed.size() == 2000);
    const ReferenceScene reference(soupScene);
    const std::vector<RefHit> hits = reference.traceClosest(aimed);
    const std::vector<uint8_t> any = reference.traceAny(aimed);
    int misses = 0, disagreements = 0;
    for (size_t i = 0; i < aimed.size(); ++i) {
        misses += hits[i].found ? 0 : 1;
        disagreements += hits[i].found == bool(any[i]) ? 0 : 1;
        // Unnormalised toward the target: it sits at t ~ 1, so the closest hit is no farther (up to the
        // rounding of the direction to float, which a grazing triangle magnifies).
        if (hits[i].found) CHECK(hits[i].t <= 1.0 + 1e-3);
    }
    CHECK(misses == 0);
    CHECK(disagreements == 0);

    const std::vector<gpu::Ray> random = randomRays(2000, 4, {-2, -2, -2}, {2, 2, 2});
    for (const gpu::Ray& r : random) {
        CHECK(glm::all(glm::lessThanEqual(glm::abs(glm::vec3(r.origin)), glm::vec3(3.0f))));
        CHECK(glm::length(glm::vec3(r.direction)) == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(r.origin.w == 0.0f);
        CHECK(std::isinf(r.direction.w));
    }
    const std::vector<RefHit> randomHits = reference.traceClosest(random);
    const std::vector<uint8_t> randomAny = reference.traceAny(random);
    int randomDisagreements = 0, randomFound = 0;
    for (size_t i = 0; i < random.size(); ++i) {
        randomDisagreements += randomHits[i].found == bool(randomAny[i]) ? 0 : 1;
        randomFound += randomHits[i].found ? 1 : 0;
    }
    CHECK(randomDisagreements == 0);
    CHECK(randomFound > 0);
    CHECK(randomFound < 2000);

    const core::SphereSet spheres = randomSpheres(500, 5, 2.0f, 0.05f, 0.2f);
    CHECK(spheres.radii.size() == 500);
    for (float r : spheres.radii) {
        CHECK(r >= 0.05f);
        CHECK(r <= 0.2f);
    }
    const std::vector<RefHit> sphereHits = traceClosestAll(sceneOf(spheres), raysTowardPoints(sceneOf(spheres), 2000, 6));
    int sphereFound = 0;
    for (const RefHit& h : sphereHits) sphereFound += h.found ? 1 : 0;
    CHECK(sphereFound >= 1980);  // a grazing ray may round past its target sphere
}

TEST_CASE("instancedCopies matches the same geometry baked into world space") {
    const core::SceneDescription base = sceneOf(randomTriangleSoup(300, 8, 1.0f));
    const core::SceneDescription instanced = instancedCopies(base, 6, 9, 3.0f);
    REQUIRE(instanced.instances.size() == 6);
    CHECK(instanced.meshes.size() == 1);

    core::SceneDescription baked;
    for (const core::InstanceDescription& inst : instanced.instances) {
        CHECK(isTransformValid(inst.transform));
        core::TriangleMesh mesh = base.meshes[0];
        for (glm::vec3& p : mesh.positions) p = glm::vec3(inst.transform * glm::vec4(p, 1.0f));
        baked.meshes.push_back(std::move(mesh));
        baked.instances.push_back({{core::GeometryKind::Triangles, uint32_t(baked.meshes.size() - 1)}, glm::mat4(1.0f)});
    }

    const std::vector<gpu::Ray> rays = raysTowardPoints(instanced, 2000, 10);
    const std::vector<RefHit> a = traceClosestAll(instanced, rays), b = traceClosestAll(baked, rays);
    int same = 0, found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        found += a[i].found ? 1 : 0;
        if (a[i].found && b[i].found && a[i].instanceId == b[i].instanceId && a[i].primId == b[i].primId &&
            std::abs(a[i].t - b[i].t) <= 1e-4 * a[i].t)
            ++same;
    }
    CHECK(found == 2000);
    CHECK(same >= 1980);  // baking rounds the vertices to float, which can move an edge past a grazing ray
}

TEST_CASE("offset moves geometry far from the origin and the reference still finds the analytic hit") {
    const glm::vec3 delta(1e6f, 1e6f, 1e6f);
    const core::SceneDescription scene = sceneOf(unitTriangle());
    const core::SceneDescription far = offset(scene, delta);
    for (size_t i = 0; i < 3; ++i) CHECK(far.meshes[0].positions[i] == scene.meshes[0].positions[i] + delta);

    // 1e6 + 0.25 and 1e6 + 0.5 are exact in float, so the answer is exact too.
    const std::vector<gpu::Ray> rays = offsetRays(std::vector{ray({0.25f, 0.5f, 3.0f}, {0, 0, -1})}, delta);
    const RefHit hit = traceClosest(far, rays[0]);
    REQUIRE(hit.found);
    CHECK(hit.t == doctest::Approx(3.0).epsilon(1e-12));
    CHECK(hit.u == doctest::Approx(0.25).epsilon(1e-12));
    CHECK(hit.v == doctest::Approx(0.5).epsilon(1e-12));

    const core::SceneDescription farInstances = offsetInstances(scene, delta);
    CHECK(farInstances.meshes[0].positions == scene.meshes[0].positions);
    CHECK(glm::vec3(farInstances.instances[0].transform[3]) == delta);
    CHECK(traceClosest(farInstances, rays[0]).t == doctest::Approx(3.0).epsilon(1e-12));

    const bvh::Aabb bounds = worldBounds(far);
    CHECK(bounds.lo == delta);
    CHECK(bounds.hi == delta + glm::vec3(1, 1, 0));
}
