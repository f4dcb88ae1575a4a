// Cones, curves (round linear segments) and cylinder caps per end on the GPU, against analytic hits and
// the double-precision reference tracer.
#include "core/render/TraceKernels.h"
#include "tests/support/ReferenceTracer.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace ripple;
using ripple::test::testContext;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

core::SceneDescription sceneOfCones(core::ConeSet cones) {
    core::SceneDescription scene;
    scene.coneSets.push_back(std::move(cones));
    core::InstanceDescription instance;
    instance.geometry = {core::GeometryKind::Cones, 0};
    scene.instances.push_back(instance);
    return scene;
}

// Random cones (or curve polylines) in [-1, 1]^3 with radii 0.02..0.2 (one end 0 for every fourth cone).
core::ConeSet randomCones(uint32_t count, uint32_t seed, bool round) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> box(-1.0f, 1.0f), radius(0.02f, 0.2f), step(-0.3f, 0.3f);
    core::ConeSet set;
    set.round = round;
    set.caps = round ? core::CapEnds::None : core::CapEnds::Both;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 a(box(rng), box(rng), box(rng));
        const glm::vec3 b = a + glm::vec3(step(rng), step(rng), step(rng));
        const uint32_t first = uint32_t(set.positions.size());
        set.positions.insert(set.positions.end(), {a, b});
        set.radii.insert(set.radii.end(), {radius(rng), (!round && i % 4 == 0) ? 0.0f : radius(rng)});
        set.indices.emplace_back(first, first + 1);
    }
    return set;
}

// GPU closest hits against the reference: the same primitive (or a tie) at t within 1e-4 relative, for
// all but `allowedEdges` rays (grazing rays whose float answer may flip between hit and miss).
void checkAgainstReference(const core::SceneDescription& description, const std::vector<gpu::Ray>& rays,
                           size_t allowedEdges) {
    test::ValidationGuard guard;
    core::Scene scene(testContext(), description);
    core::TraceKernels kernels(testContext());
    const std::vector<gpu::Hit> hits = kernels.traceClosest(scene, rays);
    const std::vector<test::RefHit> ref = test::traceClosestAll(description, rays);
    size_t mismatches = 0, found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const bool gpuHit = hits[i].status == gpu::HIT_FOUND;
        found += ref[i].found;
        if (gpuHit != ref[i].found) { ++mismatches; continue; }
        if (!gpuHit) continue;
        const bool sameT = std::abs(double(hits[i].t) - ref[i].t) <= 1e-4 * ref[i].t + 1e-6;
        if (!sameT || (hits[i].primId != ref[i].primId && ref[i].hitCount < 2)) ++mismatches;
    }
    INFO("rays " << rays.size() << ", reference hits " << found << ", mismatches " << mismatches);
    CHECK(found > rays.size() / 10);  // the scene is really being hit
    CHECK(mismatches <= allowedEdges);
}

}  // namespace

// Analytic: a cone from (0,0,-1) radius 1 to (0,0,1) radius 0.5. A ray along -x at z = 0 meets the side
// where r = 0.75: t = 2 - 0.75; along the axis from above it meets the cap of the second end (z = 1,
// t = 2) only with caps, else the inside of the far end's cap is open and it hits nothing until... the
// side from inside is never crossed along the axis: a miss. Tolerance 1e-6 relative.
TEST_CASE("cone: analytic side and caps per end") {
    test::ValidationGuard guard;
    core::ConeSet cone;
    cone.positions = {{0, 0, -1}, {0, 0, 1}};
    cone.radii = {1.0f, 0.5f};
    const std::vector<gpu::Ray> rays = {
        {{2.0f, 0.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f, kInf}},  // side: t = 1.25, u = 0.5
        {{0.0f, 0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}},  // down the axis: second cap at t = 2
        {{0.0f, 0.0f, -3.0f, 0.0f}, {0.0f, 0.0f, 1.0f, kInf}},  // up the axis: first cap at t = 2
    };
    core::TraceKernels kernels(testContext());
    for (core::CapEnds caps : {core::CapEnds::None, core::CapEnds::First, core::CapEnds::Second, core::CapEnds::Both}) {
        cone.caps = caps;
        core::Scene scene(testContext(), sceneOfCones(cone));
        const std::vector<gpu::Hit> h = kernels.traceClosest(scene, rays);
        CAPTURE(static_cast<int>(caps));
        REQUIRE(h[0].status == gpu::HIT_FOUND);
        CHECK(h[0].t == doctest::Approx(1.25).epsilon(1e-6));
        CHECK(h[0].u == doctest::Approx(0.5).epsilon(1e-6));
        CHECK(h[0].v == 0.0f);
        const bool second = caps == core::CapEnds::Second || caps == core::CapEnds::Both;
        const bool first = caps == core::CapEnds::First || caps == core::CapEnds::Both;
        // Down the axis without the second cap, the ray enters the open end and meets the first cap from inside.
        if (second) {
            CHECK(h[1].t == doctest::Approx(2.0).epsilon(1e-6));
            CHECK(h[1].v == 1.0f);
            CHECK(h[1].u == 1.0f);
        } else if (first) {
            CHECK(h[1].t == doctest::Approx(4.0).epsilon(1e-6));
            CHECK(h[1].u == 0.0f);
        } else {
            CHECK(h[1].status == gpu::HIT_MISS);
        }
        CHECK((h[2].status == gpu::HIT_FOUND) == (first || second));
        if (first) CHECK(h[2].t == doctest::Approx(2.0).epsilon(1e-6));
    }
}

// A curve segment of equal radii is a capsule: a ray down the axis meets the end sphere at distance r
// beyond the end point. Radius 0.25, ends at z = +-1: from z = 3, t = 3 - 1.25 = 1.75, v = 2 (sphere).
TEST_CASE("curve: a segment of equal radii is a capsule") {
    test::ValidationGuard guard;
    core::ConeSet curve;
    curve.round = true;
    curve.positions = {{0, 0, -1}, {0, 0, 1}};
    curve.radii = {0.25f};
    const std::vector<gpu::Ray> rays = {{{0.0f, 0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}},
                                        {{2.0f, 0.0f, 0.3f, 0.0f}, {-1.0f, 0.0f, 0.0f, kInf}}};
    core::Scene scene(testContext(), sceneOfCones(curve));
    const std::vector<gpu::Hit> h = core::TraceKernels(testContext()).traceClosest(scene, rays);
    REQUIRE(h[0].status == gpu::HIT_FOUND);
    CHECK(h[0].t == doctest::Approx(1.75).epsilon(1e-6));
    CHECK(h[0].v == 2.0f);
    REQUIRE(h[1].status == gpu::HIT_FOUND);
    CHECK(h[1].t == doctest::Approx(1.75).epsilon(1e-6));
    CHECK(h[1].v == 0.0f);
}

// 400 random cones (caps, some with an apex) and 400 round segments, 4,000 rays through the box each:
// at most 0.5% of rays may disagree (grazing the silhouette or a cap rim).
TEST_CASE("cone and curve: random scenes agree with the reference") {
    const std::vector<gpu::Ray> rays = test::randomRays(4000, 7, glm::vec3(-1.2f), glm::vec3(1.2f));
    checkAgainstReference(sceneOfCones(randomCones(400, 1, false)), rays, 20);
    checkAgainstReference(sceneOfCones(randomCones(400, 2, true)), rays, 20);
}

// Thin cones far away: the re-centred quadratic keeps t accurate (1e-4 relative) where the textbook form
// loses every digit. Cones of radius 1e-3 at distance 1e4.
TEST_CASE("cone: thin and far away stays accurate") {
    core::ConeSet set;
    for (int i = 0; i < 20; ++i) {
        const glm::vec3 a(1e4f, float(i) * 0.01f, 0.0f);
        set.positions.insert(set.positions.end(), {a, a + glm::vec3(0.0f, 0.0f, 0.05f)});
        set.radii.insert(set.radii.end(), {1e-3f, 5e-4f});
    }
    std::vector<gpu::Ray> rays;
    for (int i = 0; i < 20; ++i)
        for (int k = 0; k < 10; ++k)
            rays.push_back({{0.0f, float(i) * 0.01f + 2e-4f * float(k - 5), 0.025f, 0.0f}, {1.0f, 0.0f, 0.0f, kInf}});
    checkAgainstReference(sceneOfCones(set), rays, 4);
}

// Bad segments are skipped and counted: NaN end, index out of range, zero length, radius 0 at both ends.
TEST_CASE("cone: validation skips bad segments") {
    core::ConeSet set;
    set.positions = {{0, 0, 0}, {0, 0, 1}, {NAN, 0, 0}, {1, 1, 1}, {1, 1, 1}};
    set.radii = {0.1f, 0.1f, 0.1f, 0.0f, 0.0f};
    set.indices = {{0, 1}, {0, 2}, {0, 9}, {3, 4}, {1, 3}};
    core::Scene scene(testContext(), sceneOfCones(set));
    CHECK(scene.report().conesKept == 2);  // {0,1} and {1,3} (radius 0.1 -> 0: an apex)
    CHECK(scene.report().conesSkipped == 3);
}
