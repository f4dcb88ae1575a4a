// Round cylinders (with and without caps) on the GPU against analytic hits and the double-precision
// reference tracer, and the validation that skips bad cylinders.
#include "core/render/TraceKernels.h"
#include "tests/support/ReferenceTracer.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"
#include "tests/support/TraceChecks.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <limits>

using namespace ripple;
using ripple::test::testContext;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

core::CylinderSet unitCylinder(bool caps) {
    core::CylinderSet set;
    set.positions = {{0, 0, -1}, {0, 0, 1}};
    set.radii = {0.5f};
    set.caps = caps ? core::CapEnds::Both : core::CapEnds::None;
    return set;
}

}  // namespace

// Rays with analytic answers: from outside through the side, along the axis onto a cap (a miss without
// caps: the ray runs inside the open tube), and from inside (the far root, or the cap). Tolerance 1e-6
// relative: a few float ULPs of the values involved.
TEST_CASE("cylinder: analytic distances, axial fraction and cap flag") {
    test::ValidationGuard guard;
    const std::vector<gpu::Ray> rays = {
        {{2.0f, 0.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f, kInf}},   // side at x = 0.5: t = 1.5, u = 0.5
        {{2.0f, 0.0f, 0.5f, 0.0f}, {-2.0f, 0.0f, 0.0f, kInf}},   // non-unit direction: t = 0.75, u = 0.75
        {{0.0f, 0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}},   // along the axis: cap at z = 1, t = 2
        {{0.0f, 0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f, kInf}},    // from the centre: t = 0.5
        {{0.1f, 0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}},   // from inside toward the bottom cap: t = 1
        {{2.0f, 0.0f, 2.0f, 0.0f}, {-1.0f, 0.0f, 0.0f, kInf}},   // beyond the end: a miss
    };
    core::Scene capped(testContext(), test::sceneOf(unitCylinder(true)));
    core::Scene open(testContext(), test::sceneOf(unitCylinder(false)));
    core::TraceKernels kernels(testContext());
    const auto c = kernels.traceClosest(capped, rays);
    const auto o = kernels.traceClosest(open, rays);
    auto expectHit = [](const gpu::Hit& h, float t, float u, float v) {
        REQUIRE(h.status == gpu::HIT_FOUND);
        CHECK(h.t == doctest::Approx(t).epsilon(1e-6));
        CHECK(h.u == doctest::Approx(u).epsilon(1e-6));
        CHECK(h.v == v);
        CHECK(h.primId == 0);
    };
    expectHit(c[0], 1.5f, 0.5f, 0.0f);
    expectHit(c[1], 0.75f, 0.75f, 0.0f);
    expectHit(c[2], 2.0f, 1.0f, 1.0f);
    expectHit(c[3], 0.5f, 0.5f, 0.0f);
    expectHit(c[4], 1.0f, 0.0f, 1.0f);
    CHECK(c[5].status == gpu::HIT_MISS);
    expectHit(o[0], 1.5f, 0.5f, 0.0f);
    CHECK(o[2].status == gpu::HIT_MISS);
    CHECK(o[4].status == gpu::HIT_MISS);
    // The reference agrees with the same analytic values.
    const auto ref = test::traceClosestAll(test::sceneOf(unitCylinder(true)), rays);
    CHECK(ref[2].t == doctest::Approx(2.0));
    CHECK(ref[2].v == 1.0);
    CHECK(ref[4].u == 0.0);
    CHECK_FALSE(ref[5].found);
}

TEST_CASE("random cylinders with caps equal the reference") {
    const auto scene = test::sceneOf(test::randomCylinders(400, 31, /*caps=*/true, 1.0f, 0.01f, 0.15f));
    test::checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 32));
    test::checkAgainstReference(scene, test::randomRays(4096, 33, glm::vec3(-1), glm::vec3(1)));
    test::checkAgainstReference(scene, test::raysTowardPoints(scene, 2048, 34, /*normalised=*/false));
}

TEST_CASE("random open cylinders equal the reference") {
    const auto scene = test::sceneOf(test::randomCylinders(400, 35, /*caps=*/false, 1.0f, 0.01f, 0.15f));
    test::checkAgainstReference(scene, test::raysTowardPoints(scene, 4096, 36));
    test::checkAgainstReference(scene, test::randomRays(4096, 37, glm::vec3(-1), glm::vec3(1)));
}

TEST_CASE("instanced cylinders beside meshes and spheres equal the reference, also far from the origin") {
    core::SceneDescription base = test::sceneOf(test::randomCylinders(150, 38, true, 0.5f, 0.02f, 0.1f));
    base.meshes.push_back(test::randomTriangleSoup(300, 39, 0.5f));
    base.instances.push_back({{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f)});
    base.sphereSets.push_back(test::randomSpheres(60, 40, 0.5f, 0.02f, 0.1f));
    base.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)});
    const auto scene = test::instancedCopies(base, 8, 41);
    const auto rays = test::raysTowardPoints(scene, 4096, 42);
    test::checkAgainstReference(scene, rays);
    // At 1e4 float positions are ~1e-3 apart, 1-5% of these radii: a few percent of the rays pass within
    // that of a silhouette or rim (edge cases). None may be wrong.
    const glm::vec3 delta(1e4f, -5e3f, 2.5e3f);
    test::checkAgainstReference(test::offsetInstances(scene, delta), test::offsetRays(rays, delta), 0.95);
}

TEST_CASE("bad cylinders are skipped, counted and named; the rest equal the reference") {
    test::ValidationGuard guard;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    core::CylinderSet set;
    set.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {nan, 0, 0}, {2, 0, 1}};
    set.indices = {{0, 1}, {2, 3}, {4, 1}, {0, 9}, {5, 1}, {1, 5}};
    set.radii = {0.2f, 0.2f, 0.2f, 0.2f, -1.0f, 0.1f};
    core::SceneDescription d = test::sceneOf(set);
    core::CylinderSet wrongRadii = set;
    wrongRadii.radii = {0.1f, 0.2f};
    d.cylinderSets.push_back(wrongRadii);
    d.instances.push_back({{core::GeometryKind::Cylinders, 1}, glm::mat4(1.0f)});
    d.instances.push_back({{core::GeometryKind::Cylinders, 4}, glm::mat4(1.0f)});
    core::Scene scene(testContext(), d);
    const core::SceneReport& rep = scene.report();
    CHECK(rep.cylindersKept == 2);
    CHECK(rep.cylindersSkipped == 4 + 6);
    CHECK(rep.instancesKept == 1);
    CHECK(rep.instancesSkipped == 2);
    auto mentions = [&](const std::string& text) {
        return std::any_of(rep.messages.begin(), rep.messages.end(), [&](const std::string& m) { return m.find(text) != std::string::npos; });
    };
    CHECK(mentions("cylinder set 0: skipped 1 cylinder(s) of zero length"));
    CHECK(mentions("cylinder set 0: skipped 1 cylinder(s) with a NaN or Inf end"));
    CHECK(mentions("cylinder set 0: skipped 1 cylinder(s) with an index out of range"));
    CHECK(mentions("cylinder set 0: skipped 1 cylinder(s) with a radius"));
    CHECK(mentions("cylinder set 1: 2 radii for 6 cylinders"));
    CHECK(mentions("instance 2: references cylinder set 4"));
    const test::ReferenceScene reference(d);
    CHECK(reference.validCylinderCount() == 2);
    test::checkAgainstReference(d, test::randomRays(4096, 43, glm::vec3(-1), glm::vec3(2)));
}
