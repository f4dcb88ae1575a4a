// GPU traversal (closest-hit and any-hit) against the double-precision brute-force reference, plus the
// edge cases of the foundation issue: watertightness, empty and huge scenes, far-from-origin geometry,
// bad input, out-of-memory, and traversals longer than lavapipe's loop cap.
#include "core/render/TraceKernels.h"
#include "tests/support/ReferenceTracer.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"
#include "tests/support/TraceChecks.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace ripple;
using ripple::test::testContext;

using test::Agreement;
using test::checkAgainstReference;
using test::compareClosest;
using test::traceOnGpu;
using test::TraceResults;

TEST_CASE("random triangle soup: closest and any hit equal the reference") {
    const auto scene = test::sceneOf(test::randomTriangleSoup(3000, 1));
    const auto rays = test::raysTowardPoints(scene, 4096, 2);
    checkAgainstReference(scene, rays);
    const auto random = test::randomRays(4096, 3, glm::vec3(-1), glm::vec3(1));
    checkAgainstReference(scene, random);
    checkAgainstReference(scene, test::raysTowardPoints(scene, 2048, 4, /*normalised=*/false));
}

TEST_CASE("degenerate and needle triangles: invalid ones skipped, the rest equal the reference") {
    test::ValidationGuard guard;
    const auto scene = test::sceneOf(test::degenerateAndNeedleMesh(5));
    core::Scene gpuScene(testContext(), scene);
    CHECK(gpuScene.report().trianglesKept == test::DegenerateMeshLayout::kept);
    CHECK(gpuScene.report().trianglesSkipped == test::DegenerateMeshLayout::total - test::DegenerateMeshLayout::kept);
    // Rays aim at points of needles and slivers, most within float resolution of an edge: no ray may be
    // wrong, but only the ordinary triangles' rays can be expected exact.
    const Agreement a = checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 6), 0.5);
    MESSAGE("degenerate mesh: exact " << a.exact << ", ties " << a.ties << ", edge " << a.edges << " of " << a.total());
}

TEST_CASE("spheres from outside and inside equal the reference") {
    const auto scene = test::sceneOf(test::randomSpheres(400, 7, 1.0f, 0.01f, 0.2f));
    checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 8));
    checkAgainstReference(scene, test::randomRays(4096, 9, glm::vec3(-1), glm::vec3(1)));
}

TEST_CASE("instanced copies of meshes and spheres equal the reference") {
    core::SceneDescription base = test::sceneOf(test::randomTriangleSoup(500, 10, 0.5f));
    base.sphereSets.push_back(test::randomSpheres(100, 11, 0.5f, 0.02f, 0.1f));
    base.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)});
    const auto scene = test::instancedCopies(base, 12, 12);
    checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 13));
    checkAgainstReference(scene, test::raysTowardPoints(scene, 2048, 14, /*normalised=*/false));
}

// Geometries of 1 to 12 primitives, instanced: BLASes of one leaf (nested spheres: no split helps), and
// roots holding several children, leaves among them.
TEST_CASE("instances of small geometries (one leaf, or a root of several) equal the reference") {
    core::SceneDescription base;
    for (uint32_t n = 1; n <= 12; ++n) {
        base.meshes.push_back(test::randomTriangleSoup(n, 100 + n, 0.3f));
        base.instances.push_back({{core::GeometryKind::Triangles, n - 1}, glm::mat4(1.0f)});
        base.sphereSets.push_back(test::randomSpheres(n, 200 + n, 0.3f, 0.02f, 0.08f));
        base.instances.push_back({{core::GeometryKind::Spheres, n - 1}, glm::mat4(1.0f)});
    }
    // Nested spheres about one center: no split helps, so each set up to 8 is one leaf of all of them.
    for (uint32_t n = 2; n <= 8; ++n) {
        core::SphereSet nested;
        for (uint32_t i = 0; i < n; ++i) {
            nested.centers.push_back(glm::vec3(0.001f * float(i)));
            nested.radii.push_back(0.05f + 0.01f * float((i * 5) % n));
        }
        base.sphereSets.push_back(nested);
        base.instances.push_back({{core::GeometryKind::Spheres, uint32_t(base.sphereSets.size() - 1)}, glm::mat4(1.0f)});
    }
    const auto scene = test::instancedCopies(base, 4, 15, 1.5f);
    checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 16));
    checkAgainstReference(scene, test::randomRays(4096, 17, glm::vec3(-2), glm::vec3(2)));
}

TEST_CASE("watertight: rays from inside a closed perturbed sphere never miss") {
    test::ValidationGuard guard;
    const core::TriangleMesh mesh = test::perturbedSphereMesh(5, 15, 0.1f);
    REQUIRE(test::isClosedManifold(mesh));
    const auto scene = test::sceneOf(mesh);
    const auto rays = test::raysFromInside(glm::vec3(0.0f), 200000, 16, 0.3f);
    const TraceResults r = traceOnGpu(scene, rays);
    const auto misses = std::count_if(r.closest.begin(), r.closest.end(), [](const gpu::Hit& h) { return h.status != gpu::HIT_FOUND; });
    const auto anyMisses = std::count(r.any.begin(), r.any.end(), gpu::HIT_MISS);
    CHECK(misses == 0);
    CHECK(anyMisses == 0);
}

TEST_CASE("empty scene: every ray misses") {
    test::ValidationGuard guard;
    const auto rays = test::randomRays(1000, 17, glm::vec3(-1), glm::vec3(1));
    const TraceResults r = traceOnGpu(core::SceneDescription{}, rays);
    CHECK(std::all_of(r.closest.begin(), r.closest.end(), [](const gpu::Hit& h) { return h.status == gpu::HIT_MISS; }));
    CHECK(std::all_of(r.any.begin(), r.any.end(), [](uint32_t o) { return o == gpu::HIT_MISS; }));
}

TEST_CASE("one triangle: analytic distance and barycentrics") {
    test::ValidationGuard guard;
    core::TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const gpu::Ray ray{{0.25f, 0.5f, 2.0f, 0.0f}, {0.0f, 0.0f, -1.0f, std::numeric_limits<float>::infinity()}};
    const TraceResults r = traceOnGpu(test::sceneOf(mesh), std::span(&ray, 1));
    REQUIRE(r.closest[0].status == gpu::HIT_FOUND);
    CHECK(r.closest[0].t == doctest::Approx(2.0).epsilon(1e-6));
    CHECK(r.closest[0].u == doctest::Approx(0.25).epsilon(1e-6));
    CHECK(r.closest[0].v == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(r.closest[0].primId == 0);
    CHECK(r.any[0] == gpu::HIT_FOUND);
    // tmax before the triangle: a miss for both kernels.
    gpu::Ray shortRay = ray;
    shortRay.direction.w = 1.5f;
    const TraceResults s = traceOnGpu(test::sceneOf(mesh), std::span(&shortRay, 1));
    CHECK(s.closest[0].status == gpu::HIT_MISS);
    CHECK(s.any[0] == gpu::HIT_MISS);
}

TEST_CASE("a mesh of over a million triangles equals the reference on sampled rays") {
    const auto scene = test::sceneOf(test::gridMesh(1'000'000));
    checkAgainstReference(scene, test::raysTowardPoints(scene, 256, 18));
}

TEST_CASE("far from the origin: offsets up to 1e6 equal the reference") {
    const auto base = test::sceneOf(test::randomTriangleSoup(2000, 19));
    const auto baseRays = test::raysTowardPoints(base, 2048, 20);
    for (float distance : {1e3f, 1e5f, 1e6f}) {
        CAPTURE(distance);
        const glm::vec3 delta(distance, -0.5f * distance, 0.25f * distance);
        checkAgainstReference(test::offset(base, delta), test::offsetRays(baseRays, delta), 0.99);
        checkAgainstReference(test::offsetInstances(base, delta), test::offsetRays(baseRays, delta), 0.99);
    }
}

TEST_CASE("bad input is skipped, counted and named; it is never hit") {
    test::ValidationGuard guard;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    core::SceneDescription d;
    core::TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, {0, inf, 0}};
    mesh.indices = {{0, 1, 2}, {0, 1, 3}, {0, 4, 2}, {0, 1, 99}};
    d.meshes.push_back(mesh);
    d.meshes.push_back({});  // empty mesh
    d.sphereSets.push_back({{{0, 0, 5}, {0, 0, 7}, {nan, 0, 0}}, {1.0f, 0.0f, 1.0f}});
    d.instances = {{{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Triangles, 1}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Triangles, 7}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Triangles, 0}, glm::mat4(0.0f)},
                   {{static_cast<core::GeometryKind>(5), 0}, glm::mat4(1.0f)}};
    core::Scene scene(testContext(), d);
    const core::SceneReport& rep = scene.report();
    CHECK(rep.trianglesKept == 1);
    CHECK(rep.trianglesSkipped == 3);
    CHECK(rep.spheresKept == 1);
    CHECK(rep.spheresSkipped == 2);
    CHECK(rep.instancesKept == 2);
    CHECK(rep.instancesSkipped == 4);
    auto mentions = [&](const std::string& text) {
        return std::any_of(rep.messages.begin(), rep.messages.end(), [&](const std::string& m) { return m.find(text) != std::string::npos; });
    };
    CHECK(mentions("mesh 0: skipped 1 triangle(s) with an index out of range"));
    CHECK(mentions("mesh 0: skipped 2 triangle(s) with a NaN or Inf vertex"));
    CHECK(mentions("instance 1: mesh 1 has no valid primitives"));
    CHECK(mentions("sphere set 0: skipped 1 sphere(s) with a radius"));
    CHECK(mentions("instance 3: references mesh 7"));
    CHECK(mentions("instance 4: transform"));
    CHECK(mentions("instance 5: unknown geometry kind 5"));
    const auto rays = test::randomRays(4096, 21, glm::vec3(-2), glm::vec3(2));
    checkAgainstReference(d, rays);
}

TEST_CASE("out of GPU memory is an error naming the allocation") {
    test::ValidationGuard guard;
    try {
        vk::Buffer huge(testContext(), VkDeviceSize(1) << 50, "deliberately huge test buffer");
        FAIL("a 1 PiB allocation succeeded");
    } catch (const vk::VulkanError& e) {
        CHECK(std::string(e.what()).find("deliberately huge test buffer") != std::string::npos);
        CHECK(e.result() == VK_ERROR_OUT_OF_DEVICE_MEMORY);
    }
}

// 150,000 tilted triangles over the same square, sharing one edge, with the third vertex at scrambled
// heights: every box is the same, so the BVH cannot cull and a downward ray must test all of them, far
// beyond the iterations lavapipe lets one invocation run (see core::kMaxStepBudget). Without the step
// budget the loop is cut off silently and returns a lower triangle (seen while writing this test). With
// resume rounds the top triangle must be found exactly; without them, or without enough resume slots,
// every unfinished ray must be flagged, never silently wrong.
TEST_CASE("traversal longer than the per-invocation loop cap: resumed exactly, or flagged") {
    test::ValidationGuard guard;
    core::TriangleMesh stack;
    const uint32_t layers = 150000;
    for (uint32_t i = 0; i < layers; ++i) {
        const float h = float(1 + (i * 7919u) % layers) / float(layers + 1);  // in (0, 1), all distinct
        stack.positions.insert(stack.positions.end(), {{-4, -4, 0}, {4, -4, 1}, {0, 4, h}});
    }
    const auto scene = test::sceneOf(stack);
    std::vector<gpu::Ray> rays;
    for (int i = 0; i < 64; ++i)
        rays.push_back({{-0.5f + float(i % 8) / 8.0f, -0.5f + float(i / 8) / 8.0f, 2.0f, 0.0f},
                        {0.0f, 0.0f, -1.0f, std::numeric_limits<float>::infinity()}});
    const auto ref = test::traceClosestAll(scene, rays);

    core::Scene gpuScene(testContext(), scene);
    {
        core::TraceKernels resumed(testContext(), {.resumeRounds = 12, .traversal = core::Traversal::Software});
        const Agreement a = compareClosest(scene, rays, resumed.traceClosest(gpuScene, rays), ref);
        CHECK(a.exact == rays.size());
        const auto occluded = resumed.traceAny(gpuScene, rays);
        CHECK(std::count(occluded.begin(), occluded.end(), gpu::HIT_FOUND) == 64);
    }
    {
        core::TraceKernels unresumed(testContext(), {.resumeRounds = 0, .traversal = core::Traversal::Software});
        const Agreement a = compareClosest(scene, rays, unresumed.traceClosest(gpuScene, rays), ref);
        CHECK(a.flagged == rays.size());
    }
    {
        core::TraceKernels cramped(testContext(), {.resumeRounds = 12, .resumeCapacity = 16, .traversal = core::Traversal::Software});
        const Agreement a = compareClosest(scene, rays, cramped.traceClosest(gpuScene, rays), ref);
        CHECK(a.flagged >= rays.size() - 16);
        CHECK(a.flagged < rays.size());
        CHECK(a.wrong == 0);
    }
    {
        // A tiny budget on an ordinary scene: many rounds of parking give exactly the unbudgeted answer.
        const auto soup = test::sceneOf(test::randomTriangleSoup(3000, 22));
        const auto soupRays = test::raysTowardPoints(soup, 2048, 23);
        core::Scene soupScene(testContext(), soup);
        core::TraceKernels tiny(testContext(), {.stepBudget = core::kMinStepBudget, .resumeRounds = 400, .traversal = core::Traversal::Software});
        core::TraceKernels normal(testContext(), {.traversal = core::Traversal::Software});
        const auto a = tiny.traceClosest(soupScene, soupRays);
        const auto b = normal.traceClosest(soupScene, soupRays);
        uint64_t same = 0;
        for (size_t i = 0; i < a.size(); ++i)
            same += a[i].status == b[i].status && a[i].t == b[i].t && a[i].primId == b[i].primId;
        CHECK(same == a.size());
    }
}

// Large random triangles filling a cube, instanced three times with small shifts: every box overlaps every
// other, so many rays visit hundreds of nodes and triangles across all three BLASes, and a closest hit may
// lie in any of them. At the smallest step budget it parks many times: inside a BLAS leaf (parked as one
// word), in a BLAS with TLAS instances still pending, and in the last BLAS (entered without a return
// entry). Resumed, closest and any hit must equal the unbudgeted trace exactly; without resume rounds,
// every ray the budget cut must be flagged, none wrong.
TEST_CASE("several instances at the smallest step budget: resumed exactly, or flagged") {
    test::ValidationGuard guard;
    core::TriangleMesh soup;
    uint32_t state = 12345u;
    auto next = [&state] {  // a fixed LCG: the same scene on every platform
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
    };
    for (int i = 0; i < 3 * 3000; ++i) soup.positions.push_back({next(), next(), next()});
    auto scene = test::sceneOf(soup);
    const core::InstanceDescription first = scene.instances[0];
    for (int i = 1; i < 3; ++i) {
        core::InstanceDescription shifted = first;
        shifted.transform[3] = glm::vec4(0.2f * float(i), -0.1f * float(i), 0.15f * float(i), 1.0f);
        shifted.instanceId = uint32_t(i);
        scene.instances.push_back(shifted);
    }
    const auto rays = test::randomRays(1024, 26, glm::vec3(-1.5f), glm::vec3(1.5f));
    const auto ref = test::traceClosestAll(scene, rays);

    // Costly node visits make leaves of up to eight triangles, so most parks happen inside a leaf.
    core::Scene gpuScene(testContext(), scene, bvh::BuildOptions{.traversalCost = 64.0f});
    REQUIRE(gpuScene.instanceCount() == 3);
    core::TraceKernels normal(testContext(), {.traversal = core::Traversal::Software});
    const auto expected = normal.traceClosest(gpuScene, rays);
    const Agreement unbudgeted = compareClosest(scene, rays, expected, ref);
    CHECK(unbudgeted.wrong + unbudgeted.flagged == 0);
    CHECK(unbudgeted.exact > rays.size() / 2);
    // Parking and resuming change no arithmetic: the hits must be those of the unbudgeted trace, bit for bit.
    core::TraceKernels tiny(testContext(), {.stepBudget = core::kMinStepBudget, .resumeRounds = 100, .traversal = core::Traversal::Software});
    const auto resumed = tiny.traceClosest(gpuScene, rays);
    uint64_t same = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        same += resumed[i].status == expected[i].status && resumed[i].t == expected[i].t &&
                resumed[i].u == expected[i].u && resumed[i].primId == expected[i].primId &&
                resumed[i].instanceId == expected[i].instanceId;
    CHECK(same == rays.size());
    const auto occludedExpected = normal.traceAny(gpuScene, rays);
    const auto occludedResumed = tiny.traceAny(gpuScene, rays);
    CHECK(std::equal(occludedExpected.begin(), occludedExpected.end(), occludedResumed.begin()));
    // Budgets one step apart park each ray at every kind of step in turn: inside a leaf, right after an
    // inner node (the nearest child held outside the stack), right after entering an instance.
    for (uint32_t extra = 1; extra < 8; ++extra) {
        core::TraceKernels shifted(testContext(), {.stepBudget = core::kMinStepBudget + extra, .resumeRounds = 100,
                                                   .traversal = core::Traversal::Software});
        const auto hits = shifted.traceClosest(gpuScene, rays);
        uint64_t equal = 0;
        for (size_t i = 0; i < rays.size(); ++i)
            equal += hits[i].status == expected[i].status && hits[i].t == expected[i].t &&
                     hits[i].primId == expected[i].primId && hits[i].instanceId == expected[i].instanceId;
        CHECK_MESSAGE(equal == rays.size(), "step budget ", core::kMinStepBudget + extra);
        const auto occluded = shifted.traceAny(gpuScene, rays);
        CHECK_MESSAGE(std::equal(occluded.begin(), occluded.end(), occludedExpected.begin()), "step budget ",
                      core::kMinStepBudget + extra);
    }

    core::TraceKernels unresumed(testContext(), {.stepBudget = core::kMinStepBudget, .resumeRounds = 0, .traversal = core::Traversal::Software});
    const Agreement cut = compareClosest(scene, rays, unresumed.traceClosest(gpuScene, rays), ref);
    CHECK(cut.flagged > rays.size() / 8);  // 236 of 1,024 on lavapipe: the budget really cuts traversals
    CHECK(cut.wrong == 0);
}

// A device without ray queries (or a context that leaves them off): Auto is the software traversal, and
// asking for ray queries fails at once, naming what is missing, instead of tracing wrongly later.
TEST_CASE("traversal choice on a device without ray queries: Auto is software, RayQuery a clear error") {
    vk::Context plain(vk::ContextOptions{.validation = true, .printDeviceChoice = false, .rayQuery = false});
    CHECK_FALSE(plain.supportsRayQuery());
    CHECK(plain.rayQueryMissing().find("ContextOptions::rayQuery") != std::string::npos);
    core::TraceKernels kernels(plain, {.traversal = core::Traversal::Software});
    CHECK(kernels.traversal() == core::Traversal::Software);
    CHECK_THROWS_WITH_AS(core::TraceKernels(plain, {.traversal = core::Traversal::RayQuery}),
                         doctest::Contains("lacks"), std::runtime_error);
    CHECK_THROWS_AS(core::Scene(plain, test::sceneOf(test::randomTriangleSoup(10, 1)), {}, nullptr,
                                core::Traversal::RayQuery),
                    std::runtime_error);
    core::Scene scene(plain, test::sceneOf(test::randomTriangleSoup(10, 1)), {}, nullptr, core::Traversal::Software);
    CHECK(scene.traversal() == core::Traversal::Software);
    CHECK(scene.report().accelerationStructureBytes == 0);
    CHECK(core::parseTraversal("rayQuery") == core::Traversal::RayQuery);
    CHECK_FALSE(core::parseTraversal("hardware").has_value());
    CHECK(plain.validationMessageCount() == 0);
}
