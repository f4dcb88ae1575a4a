// The ray-query back-end (VK_KHR_ray_query over Vulkan acceleration structures) against Ripple's own BVH4
// traversal: the same rays at scenes of every geometry kind through both, hits compared ray by ray.
// Runs only where the device has ray queries (ray_query_main.cpp skips the suite elsewhere).
#include "core/render/PathTracer.h"
#include "core/render/TraceKernels.h"
#include "metrics/ImageMetrics.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>
#include <random>

using namespace ripple;
using ripple::test::testContext;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Random cones with caps (every fourth one a point at one end), or round curve segments, in [-1, 1]^3.
core::ConeSet randomCones(uint32_t count, uint32_t seed, bool round) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> box(-1.0f, 1.0f), radius(0.02f, 0.15f), step(-0.3f, 0.3f);
    core::ConeSet set;
    set.round = round;
    set.caps = round ? core::CapEnds::None : core::CapEnds::Both;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 a(box(rng), box(rng), box(rng));
        set.positions.insert(set.positions.end(), {a, a + glm::vec3(step(rng), step(rng), step(rng))});
        set.radii.insert(set.radii.end(), {radius(rng), (!round && i % 4 == 0) ? 0.0f : radius(rng)});
    }
    return set;
}

// Every kind once: a triangle soup, spheres, capped cylinders, capped cones and round curves.
core::SceneDescription everyKind() {
    core::SceneDescription scene;
    scene.meshes.push_back(test::randomTriangleSoup(2000, 31));
    scene.sphereSets.push_back(test::randomSpheres(300, 32));
    scene.cylinderSets.push_back(test::randomCylinders(300, 33, true));
    scene.coneSets.push_back(randomCones(300, 34, false));
    scene.coneSets.push_back(randomCones(300, 35, true));
    const core::GeometryRef refs[] = {{core::GeometryKind::Triangles, 0}, {core::GeometryKind::Spheres, 0},
                                      {core::GeometryKind::Cylinders, 0}, {core::GeometryKind::Cones, 0},
                                      {core::GeometryKind::Cones, 1}};
    for (const core::GeometryRef& ref : refs) {
        core::InstanceDescription instance;
        instance.geometry = ref;
        scene.instances.push_back(instance);
    }
    return scene;
}

// `copies` more instances of every instance, each under a random rotation, non-uniform scale and
// translation: the copies share their geometry's BLAS.
core::SceneDescription withCopies(core::SceneDescription scene, uint32_t copies, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), scale(0.5f, 2.0f);
    const size_t base = scene.instances.size();
    for (uint32_t k = 0; k < copies; ++k)
        for (size_t i = 0; i < base; ++i) {
            core::InstanceDescription copy = scene.instances[i];
            glm::mat4 m = glm::translate(glm::mat4(1.0f), 3.0f * glm::vec3(unit(rng), unit(rng), unit(rng)));
            m = glm::rotate(m, 3.14159f * unit(rng), glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + 1e-3f));
            m = glm::scale(m, glm::vec3(scale(rng), scale(rng), scale(rng)));
            copy.transform = m * copy.transform;
            copy.instanceId = uint32_t(scene.instances.size());
            scene.instances.push_back(copy);
        }
    return scene;
}

// Rays at the scene: random origins and directions across its bounds, half of them with a non-unit
// direction, some with tmin > 0 or a finite tmax.
std::vector<gpu::Ray> mixedRays(const core::SceneDescription& scene, uint32_t count, uint32_t seed) {
    bvh::Aabb bounds = test::worldBounds(scene);
    if (!(bounds.lo.x <= bounds.hi.x)) bounds = {glm::vec3(-1.0f), glm::vec3(1.0f)};
    std::vector<gpu::Ray> rays = test::randomRays(count, seed, bounds.lo, bounds.hi);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> length(0.2f, 5.0f);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (i % 2 == 1) rays[i].direction = gpu::vec4(glm::vec3(rays[i].direction) * length(rng), kInf);
        if (i % 7 == 3) rays[i].origin.w = 0.3f;
        if (i % 5 == 2) rays[i].direction.w = 1.5f;
    }
    return rays;
}

struct BothBackEnds {
    core::TraceKernels software{testContext(), {.traversal = core::Traversal::Software}};
    core::TraceKernels rayQuery{testContext(), {.traversal = core::Traversal::RayQuery}};
};

BothBackEnds& backEnds() {
    static BothBackEnds kernels;
    return kernels;
}

// Closest hits of the two back-ends, per ray: the same status, and where both hit, the same instance
// and primitive with t within 1e-4 relative, or a tie (another primitive at t within 1e-4 relative).
// Grazing rays (a sphere's silhouette, a cylinder's rim, a triangle's edge) may flip between hit and
// miss, or between neighbours, as the two compute in different spaces and orders; at most
// `grazingFraction` of the rays may do so. Any-hit status likewise. No ray may be flagged.
void checkAgreement(const core::SceneDescription& description, const std::vector<gpu::Ray>& rays,
                    double grazingFraction, bool expectHits = true) {
    test::ValidationGuard guard;
    core::Scene softwareScene(testContext(), description, {}, nullptr, core::Traversal::Software);
    core::Scene rqScene(testContext(), description, {}, nullptr, core::Traversal::RayQuery);
    REQUIRE(rqScene.traversal() == core::Traversal::RayQuery);
    const auto a = backEnds().software.traceClosest(softwareScene, rays);
    const auto b = backEnds().rayQuery.traceClosest(rqScene, rays);
    size_t statusDiffers = 0, hits = 0, same = 0, ties = 0, farT = 0, flagged = 0, uvDiffers = 0;
    double worstT = 0.0;
    for (size_t i = 0; i < rays.size(); ++i) {
        flagged += (a[i].status | b[i].status) > gpu::HIT_FOUND;
        if (a[i].status != b[i].status) { ++statusDiffers; continue; }
        if (a[i].status != gpu::HIT_FOUND) continue;
        ++hits;
        const double rel = std::abs(double(a[i].t) - double(b[i].t)) / std::max(1e-6, double(a[i].t));
        const bool samePrim = a[i].instanceId == b[i].instanceId && a[i].primId == b[i].primId;
        if (rel > 1e-4) ++farT;
        else if (samePrim) {
            ++same;
            worstT = std::max(worstT, rel);
            uvDiffers += std::abs(a[i].u - b[i].u) > 1e-3f || std::abs(a[i].v - b[i].v) > 1e-3f;
        } else ++ties;
    }
    const auto occludedA = backEnds().software.traceAny(softwareScene, rays);
    const auto occludedB = backEnds().rayQuery.traceAny(rqScene, rays);
    size_t anyDiffers = 0, anyFlagged = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        anyDiffers += occludedA[i] != occludedB[i];
        anyFlagged += (occludedA[i] | occludedB[i]) > gpu::HIT_FOUND;
    }
    const auto allowed = size_t(grazingFraction * double(rays.size()));
    INFO("rays " << rays.size() << ", both hit " << hits << " (same primitive " << same << ", ties " << ties
                 << ", t apart " << farT << "), status differs " << statusDiffers << ", any-hit differs "
                 << anyDiffers << ", worst relative t " << worstT << ", u/v apart " << uvDiffers);
    CHECK(flagged == 0);
    CHECK(anyFlagged == 0);
    if (expectHits) CHECK(hits > rays.size() / 10);  // the scene is really being hit
    CHECK(statusDiffers + farT + ties <= allowed);
    CHECK(uvDiffers <= allowed);
    CHECK(anyDiffers <= allowed);
}

}  // namespace

TEST_SUITE("ray query") {

TEST_CASE("ray query: every geometry kind agrees with the software traversal") {
    const core::SceneDescription scene = everyKind();
    std::vector<gpu::Ray> rays = mixedRays(scene, 20000, 41);
    const auto toward = test::raysTowardPoints(scene, 10000, 42, false);  // triangles, spheres, cylinders
    rays.insert(rays.end(), toward.begin(), toward.end());
    checkAgreement(scene, rays, 0.002);
}

TEST_CASE("ray query: each kind alone") {
    const core::SceneDescription scene = everyKind();
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        core::SceneDescription alone = scene;
        alone.instances = {scene.instances[i]};
        CAPTURE(i);
        checkAgreement(alone, mixedRays(alone, 8000, 50 + uint32_t(i)), 0.002);
    }
}

TEST_CASE("ray query: instances under non-trivial transforms sharing BLASes") {
    const core::SceneDescription scene = withCopies(everyKind(), 3, 61);
    REQUIRE(scene.instances.size() == 20);
    core::Scene rqScene(testContext(), scene, {}, nullptr, core::Traversal::RayQuery);
    CHECK(rqScene.report().accelerationStructuresBuilt == 5);  // one per geometry, shared by its copies
    CHECK(rqScene.report().accelerationStructureBytes > 0);
    checkAgreement(scene, mixedRays(scene, 20000, 62), 0.002);
}

TEST_CASE("ray query: an empty scene reports misses") {
    test::ValidationGuard guard;
    core::SceneDescription empty;
    core::Scene scene(testContext(), empty, {}, nullptr, core::Traversal::RayQuery);
    const auto rays = test::randomRays(256, 71, glm::vec3(-1.0f), glm::vec3(1.0f));
    for (const gpu::Hit& hit : backEnds().rayQuery.traceClosest(scene, rays)) CHECK(hit.status == gpu::HIT_MISS);
    for (uint32_t status : backEnds().rayQuery.traceAny(scene, rays)) CHECK(status == gpu::HIT_MISS);
    checkAgreement(empty, rays, 0.0, false);
}


// 150,000 stacked triangles that every ray's box tests pass through (the software suite's loop-cap scene,
// traversal_test.cpp): the device's traversal inside rayQueryProceedEXT visits hundreds of thousands of
// nodes for one ray. Mesa 22.3's lavapipe silently ended any shader loop after 65,535 iterations; a cut
// there must show as HIT_FLAG_RAN_OUT, never as a wrong triangle: each ray finds the software trace's
// triangle at t within 1e-5 relative (the two compute t differently), or is flagged. (Mesa 25.0 finishes
// every ray.)
TEST_CASE("ray query: a traversal of 150,000 overlapping triangles is exact or flagged") {
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
        rays.push_back({{-0.5f + float(i % 8) / 8.0f, -0.5f + float(i / 8) / 8.0f, 2.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}});
    core::Scene softwareScene(testContext(), scene, {}, nullptr, core::Traversal::Software);
    core::Scene rqScene(testContext(), scene, {}, nullptr, core::Traversal::RayQuery);
    core::TraceKernels resumed(testContext(), {.resumeRounds = 12, .traversal = core::Traversal::Software});
    const auto expected = resumed.traceClosest(softwareScene, rays);
    const auto hits = backEnds().rayQuery.traceClosest(rqScene, rays);
    const auto occluded = backEnds().rayQuery.traceAny(rqScene, rays);
    size_t exact = 0, flagged = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        REQUIRE(expected[i].status == gpu::HIT_FOUND);
        if (hits[i].status & gpu::HIT_FLAG_RAN_OUT) ++flagged;
        else exact += hits[i].status == gpu::HIT_FOUND && hits[i].primId == expected[i].primId &&
                      std::abs(hits[i].t - expected[i].t) <= 1e-5f * expected[i].t;  // last bits may differ
        CHECK((occluded[i] == gpu::HIT_FOUND || (occluded[i] & gpu::HIT_FLAG_RAN_OUT) != 0));
    }
    MESSAGE("exact " << exact << ", flagged " << flagged << " of " << rays.size());
    CHECK(exact + flagged == rays.size());
}

// 20,000 spheres along the x axis whose boxes the axis pierces but whose surfaces it misses, then one
// sphere on the axis: each box is an AABB candidate the kernel must reject, more than its bound on
// candidates per ray (RQ_MAX_PROCEEDS, traverse_rq.glsl). The ray along the axis must come back
// flagged HIT_FLAG_RAN_OUT, never as a miss; a ray beside the stack hits the last sphere exactly.
TEST_CASE("ray query: more AABB candidates than the kernel's bound are flagged, never a silent miss") {
    test::ValidationGuard guard;
    core::SphereSet spheres;
    const uint32_t decoys = 20000;
    for (uint32_t i = 0; i < decoys; ++i) spheres.centers.push_back({0.1f * float(i), 0.04f, 0.04f});
    spheres.centers.push_back({0.1f * float(decoys), 0.0f, 0.0f});
    spheres.radii = {0.045f};  // the axis passes 0.057 from each decoy's center: inside its box, outside it
    const auto scene = test::sceneOf(spheres);
    const float start = -1.0f, end = 0.1f * float(decoys);
    const std::vector<gpu::Ray> rays = {
        {{start, 0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f, kInf}},              // through every decoy box
        {{end, 0.0f, 5.0f, 0.0f}, {0.0f, 0.0f, -1.0f, kInf}}};               // straight at the last sphere
    core::Scene rqScene(testContext(), scene, {}, nullptr, core::Traversal::RayQuery);
    const auto hits = backEnds().rayQuery.traceClosest(rqScene, rays);
    CHECK((hits[0].status & gpu::HIT_FLAG_RAN_OUT) != 0);
    CHECK(hits[1].status == gpu::HIT_FOUND);
    CHECK(hits[1].primId == decoys);
    CHECK(hits[1].t == doctest::Approx(5.0f - 0.045f).epsilon(1e-5));
    // Any-hit stops at the first confirmed candidate, but the axis ray has none before the bound.
    const auto occluded = backEnds().rayQuery.traceAny(rqScene, rays);
    CHECK((occluded[0] & gpu::HIT_FLAG_RAN_OUT) != 0);
    CHECK(occluded[1] == gpu::HIT_FOUND);
}

// The path tracer over a scene of every kind on a floor, lit by a directional light and ambient light,
// through each back-end with the same seed (so the same random numbers): the two images must differ by
// less than a tenth of what separates two software renders with different seeds (relMSE, ImageMetrics.h).
// The back-ends' hits differ only in the last bits of t, u and v, so their images share their noise.
TEST_CASE("ray query: the path tracer's image agrees with the software back-end's") {
    test::ValidationGuard guard;
    core::SceneDescription description = everyKind();
    for (core::InstanceDescription& instance : description.instances)
        instance.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 1.2f));
    description.meshes.push_back(test::squareMesh(6.0f));
    core::InstanceDescription floor;
    floor.geometry = {core::GeometryKind::Triangles, uint32_t(description.meshes.size() - 1)};
    description.instances.push_back(floor);
    description.materials.push_back(core::Material{});
    core::Light sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    description.lights.push_back(sun);
    core::RenderSettings settings;
    settings.pixelSamples = 16;
    settings.ambientRadiance = 0.3f;
    const glm::uvec2 size(64, 64);
    auto render = [&](core::Traversal traversal, uint32_t seed) {
        core::Scene scene(testContext(), description, {}, nullptr, traversal);
        core::PathTracer tracer(testContext(), {.traversal = traversal});
        tracer.resize(size, false);
        settings.seed = seed;
        tracer.render(scene, test::lookingDown(4.0f, 5.0f), settings);
        std::vector<glm::vec4> rgba(size_t(size.x) * size.y);
        tracer.readColor(core::ColorFormat::Rgba32Float, rgba.data());
        apps::LinearImage image{size.x, size.y, {}};
        for (const glm::vec4& p : rgba) image.rgb.insert(image.rgb.end(), {p.r, p.g, p.b});
        return image;
    };
    const apps::LinearImage software = render(core::Traversal::Software, 1);
    const apps::LinearImage rayQuery = render(core::Traversal::RayQuery, 1);
    const apps::LinearImage otherSeed = render(core::Traversal::Software, 2);
    const double backEnds = apps::relMse(rayQuery, software);
    const double noise = apps::relMse(otherSeed, software);
    MESSAGE("relMSE ray query vs software " << backEnds << ", software seed 2 vs seed 1 " << noise);
    CHECK(noise > 0.0);
    CHECK(backEnds < 0.1 * noise);
}

}  // TEST_SUITE
