// Volumes against analytic answers: the transmittance of a homogeneous slab (exp(-sigma d)) and of a linear
// opacity ramp (exp(-integral of the extinction)) seen against the background by camera rays through a black absorber, at
// extinctions from 1e-3 to 1e3 per unit; and a volumetric furnace (a white, non-absorbing medium under a
// uniform environment of radiance 1 looks exactly like the environment). Metric: the mean over all pixels,
// within 1% (relative) plus 4 standard errors of the Bernoulli or path noise.
#include "core/scene/VolumeTable.h"
#include "tests/support/RenderHelpers.h"

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace ripple;

namespace {

// A box volume filling [-1, 1]^2 x [0, depth] (x, y, z), `n` voxels per axis (9: one macrocell), all 1 unless
// ramp: value rises linearly from 0 at z = 0 to 1 at z = depth. The transfer function maps [0, 1] to
// opacities {0, opacity} (ramp) or {opacity, opacity}, over unitDistance.
core::Volume boxVolume(float depth, float opacity, float unitDistance, bool ramp, glm::vec3 albedo, uint32_t n = 9) {
    core::Volume v;
    v.dims = {n, n, n};
    std::vector<float> values;
    for (uint32_t z = 0; z < n; ++z)
        for (uint32_t i = 0; i < n * n; ++i) values.push_back(ramp ? float(z) / float(n - 1) : 1.0f);
    v.values = std::make_shared<const std::vector<float>>(std::move(values));
    v.origin = {-1.0f, -1.0f, 0.0f};
    v.spacing = {2.0f / float(n - 1), 2.0f / float(n - 1), depth / float(n - 1)};
    v.valueRange = {0.0f, 1.0f};
    v.colors = {albedo};
    v.opacities = ramp ? std::vector<float>{0.0f, opacity} : std::vector<float>{opacity, opacity};
    v.unitDistance = unitDistance;
    return v;
}

// A white (0.8) matte floor at z = 0, 4 units wide, lit straight down by a directional light of irradiance
// pi through `slab`, moved to start at z = 0.5: seen from below the slab, each pixel shows 0.8 times the
// slab's transmittance along the vertical.
core::SceneDescription litFloorUnder(core::Volume slab) {
    core::SceneDescription scene;
    scene.meshes.push_back(test::squareMesh(4.0f));
    core::Material white;
    white.baseColor = glm::vec3(0.8f);
    scene.materials.push_back(white);
    scene.instances.push_back({{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f), 0});
    core::Light sun;
    sun.kind = core::Light::Kind::Directional;
    sun.direction = {0.0f, 0.0f, -1.0f};
    sun.intensity = float(M_PI);
    scene.lights.push_back(sun);
    slab.origin.z = 0.5f;
    scene.volumes.push_back(slab);
    return scene;
}

}  // namespace

TEST_CASE("volumes: transmittance of a homogeneous slab and of a linear ramp, extinction 1e-3 to 1e3") {
    test::ValidationGuard guard;
    core::RenderSettings settings;
    settings.background = glm::vec4(1.0f);
    settings.maxPathLength = 1;
    settings.pixelSamples = 64;
    for (const float sigma : {1e-3f, 1.0f, 1e3f}) {
        for (const bool ramp : {false, true}) {
            // Depth so that the expected transmittance is about exp(-1) (exp(-1e-3 * 100) for the thin one).
            const float depth = sigma < 0.01f ? 100.0f : (ramp ? 2.0f : 1.0f) / sigma;
            // Opacity over unitDistance 1 / sigma gives extinction -ln(1 - o) * sigma: o = 1 - e^-1 makes it sigma.
            const float opacity = 1.0f - std::exp(-1.0f);
            core::SceneDescription scene;
            scene.volumes.push_back(boxVolume(depth, opacity, 1.0f / sigma, ramp, glm::vec3(0.0f)));
            // The ramp's opacity rises linearly with the value, o v, so its extinction is -ln(1 - o v) sigma,
            // whose mean over the depth is sigma (1 + (1 - o) ln(1 - o) / o) = 0.418 sigma.
            const double o = opacity, rampMean = 1.0 + (1.0 - o) * std::log(1.0 - o) / o;
            const double expected = std::exp(-double(sigma) * depth * (ramp ? rampMean : 1.0));
            // Above the box, every pixel looking through it.
            const test::Rendered image = test::render(scene, test::lookingDown(depth + 1.0f, 1.8f), settings, {32, 32});
            const test::Mean m = test::meanRed(image);
            CAPTURE(sigma);
            CAPTURE(ramp);
            MESSAGE("sigma " << sigma << (ramp ? " ramp" : " slab") << ": transmittance " << m.mean << " +- "
                             << m.standardError << ", expected " << expected);
            CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
            CHECK(image.stats.flaggedRays == 0);
            // Each sample either passes (1) or collides once in the black medium (0): the real collisions
            // counted on the device are exactly the samples that did not pass. A constant field's majorant is
            // its extinction, so no collision is null; the ramp's single macrocell holds the top extinction.
            double blocked = 0.0;
            for (const glm::vec4& c : image.color) blocked += (1.0 - double(c.r)) * settings.pixelSamples;
            CHECK(image.stats.realCollisions == uint64_t(std::llround(blocked)));
            if (ramp) CHECK(image.stats.nullCollisions > 0);
            else CHECK(image.stats.nullCollisions == 0);
            CHECK(image.stats.ratioCollisions == 0);  // no lights: no shadow rays
        }
    }
}

TEST_CASE("volumes: volumetric furnace, a white non-absorbing medium under a uniform environment") {
    test::ValidationGuard guard;
    core::RenderSettings settings;
    settings.background = glm::vec4(1.0f);   // camera rays that pass see 1 as well
    settings.ambientRadiance = 1.0f;
    settings.maxPathLength = 64;
    settings.pixelSamples = 32;
    const core::Camera camera = test::lookingDown(3.0f, 1.8f);
    core::SceneDescription scene;
    scene.volumes.push_back(boxVolume(2.0f, 1.0f - std::exp(-1.0f), 0.5f, false, glm::vec3(1.0f)));  // optical depth 4
    const test::Rendered image = test::render(scene, camera, settings, {24, 24});
    const test::Mean m = test::meanRed(image);
    MESSAGE("furnace: " << m.mean << " +- " << m.standardError);
    CHECK(std::abs(m.mean - 1.0) <= 0.01 + 4.0 * m.standardError);
    CHECK(image.stats.flaggedRays == 0);
}

TEST_CASE("volumes: shadow rays carry the slab's transmittance (ratio tracking)") {
    // A white matte floor at z = 0 lit straight down by a directional light of irradiance pi through an
    // absorbing slab at z in [0.5, 1.5]; the camera sits below the slab, so only the shadow rays cross it.
    // Direct light only: every pixel shows albedo * transmittance = 0.8 * exp(-sigma), or for the ramp
    // 0.8 exp(-0.418 sigma) (as in the first case). The ramp's majorant bounds it loosely, so its ratio
    // tracking takes many small steps down to about 0.03, past where Russian roulette takes over (0.1).
    test::ValidationGuard guard;
    for (const auto& [sigma, ramp] : {std::pair{1.0f, false}, std::pair{1e6f, false}, std::pair{8.0f, true}}) {
        const float opacity = 1.0f - std::exp(-1.0f);
        const core::SceneDescription scene = litFloorUnder(boxVolume(1.0f, opacity, 1.0f / sigma, ramp, glm::vec3(0.0f)));
        core::RenderSettings settings;
        settings.maxPathLength = 1;
        settings.pixelSamples = 64;
        const test::Rendered image = test::render(scene, test::lookingDown(0.4f, 1.8f), settings, {24, 24});
        const test::Mean m = test::meanRed(image);
        const double o = opacity, rampMean = 1.0 + (1.0 - o) * std::log(1.0 - o) / o;
        const double expected = 0.8 * std::exp(-double(sigma) * (ramp ? rampMean : 1.0));
        CAPTURE(ramp);
        MESSAGE("sigma " << sigma << (ramp ? " ramp" : " slab") << ": " << m.mean << " +- " << m.standardError << ", expected " << expected);
        CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError + 1e-6);
        CHECK(image.stats.flaggedRays == 0);
        // Only the shadow rays cross the slab: ratio tracking, no free flight.
        CHECK(image.stats.ratioCollisions > 0);
        CHECK(image.stats.realCollisions + image.stats.nullCollisions == 0);
    }
}

TEST_CASE("volumes: single scattering under the Henyey-Greenstein phase function, g = -0.5, 0, 0.5") {
    // A white non-absorbing slab of optical depth 1 (z in [0, 2]) lit straight down by a sun of irradiance
    // E, seen straight down from above against black. Single scattering only (maxPathLength 1): light that
    // enters at the top, collides at depth z and scatters back up (cos theta = -1 between the directions light
    // travels) is attenuated by e^(-sigma z) on each way, so the radiance is
    //   E p(-1) int_0^2 sigma e^(-2 sigma z) dz = E p(-1) (1 - e^-2) / 2,  p(-1) = (1 - g^2) / (4 pi (1 + g)^3).
    // This checks the phase function's evaluation (next-event estimation at p(-1); a wrong g or sign moves
    // it 4-27x); the case below checks its sampling against it.
    test::ValidationGuard guard;
    const double irradiance = 10.0;
    for (const float g : {-0.5f, 0.0f, 0.5f}) {
        CAPTURE(g);
        core::SceneDescription scene;
        core::Light sun;
        sun.kind = core::Light::Kind::Directional;
        sun.direction = {0.0f, 0.0f, -1.0f};
        sun.intensity = float(irradiance);
        scene.lights.push_back(sun);
        scene.volumes.push_back(boxVolume(2.0f, 1.0f - std::exp(-1.0f), 2.0f, false, glm::vec3(1.0f)));
        core::RenderSettings settings;
        settings.maxPathLength = 1;
        settings.pixelSamples = 64;
        settings.phaseAnisotropy = g;
        const test::Rendered image = test::render(scene, test::lookingDown(3.0f, 1.8f), settings, {24, 24});
        const test::Mean m = test::meanRed(image);
        const double phase = (1.0 - double(g) * g) / (4.0 * M_PI * std::pow(1.0 + g, 3.0));
        const double expected = irradiance * phase * (1.0 - std::exp(-2.0)) / 2.0;
        MESSAGE("g " << g << ": " << m.mean << " +- " << m.standardError << ", expected " << expected);
        CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
        CHECK(image.stats.flaggedRays == 0);
    }
    // And the furnace (all orders of scattering, white medium, uniform environment) stays 1 for strongly
    // forward and backward scattering: sampling the phase function keeps energy.
    for (const float g : {-0.8f, 0.8f}) {
        CAPTURE(g);
        core::RenderSettings settings;
        settings.background = glm::vec4(1.0f);
        settings.ambientRadiance = 1.0f;
        settings.maxPathLength = 64;
        settings.pixelSamples = 32;
        settings.phaseAnisotropy = g;
        core::SceneDescription scene;
        scene.volumes.push_back(boxVolume(2.0f, 1.0f - std::exp(-1.0f), 0.5f, false, glm::vec3(1.0f)));
        const test::Rendered image = test::render(scene, test::lookingDown(3.0f, 1.8f), settings, {24, 24});
        const test::Mean m = test::meanRed(image);
        MESSAGE("furnace, g " << g << ": " << m.mean << " +- " << m.standardError);
        CHECK(std::abs(m.mean - 1.0) <= 0.01 + 4.0 * m.standardError);
    }
}

TEST_CASE("volumes: extinction from 1e-6 to 1e6 in one macrocell completes without flagged rays and stays unbiased") {
    // One macrocell (3^3 voxels, so its majorant cannot separate the extremes) of depth 0.5 whose extinction is 1e-6 everywhere except next to one corner voxel,
    // where it reaches 1e6: its majorant is 1e6. With nearest filtering the march crosses the macrocell
    // under that majorant, so a ray through the thin part makes about 5e5 null collisions (lavapipe stops a
    // single loop at 65,535 iterations; the march's nested loops allow about a million steps). With linear
    // filtering the macrocell is tracked cell by cell under the interpolant's range, which separates the
    // extremes: a bounded number of null collisions. Either way rays far from the dense corner must see
    // transmittance exp(-1e-6 * 0.5), i.e. 1.
    test::ValidationGuard guard;
    for (const bool linear : {false, true}) {
        CAPTURE(linear);
        core::Volume v = boxVolume(0.5f, 0.0f, 1.0f, false, glm::vec3(0.0f), 3);
        std::vector<float> values(v.values->size(), 0.0f);
        values.back() = 1.0f;  // voxel (2, 2, 2): x = y = 1, z = 0.5; its cells reach down to x = y = 0
        v.values = std::make_shared<const std::vector<float>>(std::move(values));
        v.linearFilter = linear;
        // Opacity o over unitDistance u gives extinction -ln(1 - o) / u: o = 0.999999 (the cap) over
        // u = 13.8155 / 1e6 is 1e6; the low end is 1e-6 per unit.
        v.unitDistance = float(-std::log(1.0 - 0.999999) / 1e6);
        v.opacities = {float(1e-6 * v.unitDistance), 0.999999f};
        core::SceneDescription scene;
        scene.volumes.push_back(v);
        core::RenderSettings settings;
        settings.background = glm::vec4(1.0f);
        settings.maxPathLength = 1;
        settings.pixelSamples = 2;
        const uint32_t size = 8;
        const uint64_t rays = uint64_t(size) * size * settings.pixelSamples;
        const test::Rendered image = test::render(scene, test::lookingDown(1.5f, 1.8f), settings, {size, size});
        CHECK(image.stats.flaggedRays == 0);
        double far = 0.0;
        uint32_t count = 0;
        for (uint32_t y = 0; y < size / 2; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                far += image.at(x, y).r;  // the lower half of the image: y < 0, away from the dense corner
                ++count;
            }
        MESSAGE("null collisions " << image.stats.nullCollisions << ", parked marches " << image.stats.parkedMarches
                                    << ", far transmittance " << far / count);
        CHECK(far / count == doctest::Approx(1.0).epsilon(1e-3));
        if (linear) {
            // Cell by cell: a handful of null collisions per ray, not half a million.
            CHECK(image.stats.nullCollisions < rays * 10);
        } else {
            // The stiff path really ran: far more null collisions than a single lavapipe loop could take.
            CHECK(image.stats.nullCollisions > rays * 100000);
            // Marches of half a million steps spent the default budget per invocation (2^17) and were resumed.
            CHECK(image.stats.parkedMarches >= rays / 2);
        }
    }
}

// Every march parked after each step (a budget of one) and resumed, round after round: the answers are the
// analytic ones of the cases above, for delta tracking (camera rays through a black slab and ramp: the
// transmittance, and a real collision exactly for each sample that did not pass) and ratio tracking (shadow
// rays through a slab onto a lit floor). Without resume rounds the same marches are flagged instead. Each
// twice: extinction 1 over 33^3 voxels (4^3 macrocells, crossed whole), and extinction 3 over 3^3 voxels
// (cells of 1 x 1 x depth / 2, crossed cell by cell: an optical depth of 1.36 or more per cell crossing).
TEST_CASE("volumes: marches parked after every step and resumed give the analytic answers") {
    test::ValidationGuard guard;
    core::PathTracerOptions resumed;
    resumed.volumeParking = {.stepBudget = 1, .resumeRounds = gpu::VOLUME_MAX_RESUME_ROUNDS};
    const float opacity = 1.0f - std::exp(-1.0f);  // over unit distance u: extinction 1 / u
    for (const bool cellByCell : {false, true})
    for (const bool ramp : {false, true}) {
        CAPTURE(cellByCell);
        CAPTURE(ramp);
        core::RenderSettings settings;
        settings.background = glm::vec4(1.0f);
        settings.maxPathLength = 1;
        settings.pixelSamples = 32;
        const float depth = ramp ? 2.0f : 1.0f, sigma = cellByCell ? 3.0f : 1.0f;
        core::SceneDescription scene;
        scene.volumes.push_back(boxVolume(depth, opacity, 1.0f / sigma, ramp, glm::vec3(0.0f), cellByCell ? 3 : 33));
        CHECK(core::Scene(test::testContext(), scene).report().volumesCellByCell == (cellByCell ? 1 : 0));
        const double o = opacity, rampMean = 1.0 + (1.0 - o) * std::log(1.0 - o) / o;
        const double expected = std::exp(-double(sigma) * depth * (ramp ? rampMean : 1.0));
        const test::Rendered image = test::render(scene, test::lookingDown(depth + 1.0f, 1.8f), settings, {24, 24}, false, resumed);
        const test::Mean m = test::meanRed(image);
        MESSAGE((ramp ? "ramp" : "slab") << ": transmittance " << m.mean << " +- " << m.standardError << ", expected "
                                         << expected << ", parked marches " << image.stats.parkedMarches);
        CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
        CHECK(image.stats.flaggedRays == 0);
        // Over 4^3 macrocells every march takes several steps; over 2^3 cells most collide in the first.
        if (!cellByCell) CHECK(image.stats.parkedMarches >= uint64_t(24 * 24) * settings.pixelSamples);
        double blocked = 0.0;
        for (const glm::vec4& c : image.color) blocked += (1.0 - double(c.r)) * settings.pixelSamples;
        CHECK(image.stats.realCollisions == uint64_t(std::llround(blocked)));
        if (!ramp && !cellByCell) CHECK(image.stats.nullCollisions == 0);

        core::PathTracerOptions unresumed;
        unresumed.volumeParking = {.stepBudget = 1, .resumeRounds = 0};
        const test::Rendered flagged = test::render(scene, test::lookingDown(depth + 1.0f, 1.8f), settings, {24, 24}, false, unresumed);
        CHECK(flagged.stats.parkedMarches == 0);
        if (!cellByCell) CHECK(flagged.stats.flaggedRays >= uint64_t(24 * 24) * settings.pixelSamples / 2);
        // The same first steps (round 0 draws the same numbers): every march flagged there was parked here.
        CHECK(flagged.stats.flaggedRays > 0);
        CHECK(image.stats.parkedMarches >= flagged.stats.flaggedRays);
    }
    // Shadow rays: a white floor lit straight down through an absorbing slab of optical depth 1 (and 3), seen
    // from below the slab (as in the ratio-tracking case above): 0.8 exp(-1) (and 0.8 exp(-3)).
    for (const bool cellByCell : {false, true}) {
        CAPTURE(cellByCell);
        const float sigma = cellByCell ? 3.0f : 1.0f;
        const core::SceneDescription scene =
            litFloorUnder(boxVolume(1.0f, opacity, 1.0f / sigma, false, glm::vec3(0.0f), cellByCell ? 3 : 33));
        core::RenderSettings settings;
        settings.maxPathLength = 1;
        settings.pixelSamples = 64;
        const test::Rendered image = test::render(scene, test::lookingDown(0.4f, 1.8f), settings, {24, 24}, false, resumed);
        const test::Mean m = test::meanRed(image);
        const double expected = 0.8 * std::exp(-double(sigma));
        MESSAGE("shadow rays: " << m.mean << " +- " << m.standardError << ", expected " << expected << ", parked marches "
                                << image.stats.parkedMarches);
        CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
        CHECK(image.stats.flaggedRays == 0);
        CHECK(image.stats.ratioCollisions > 0);
        if (!cellByCell) CHECK(image.stats.parkedMarches >= uint64_t(24 * 24) * settings.pixelSamples);
        core::PathTracerOptions unresumed;
        unresumed.volumeParking = {.stepBudget = 1, .resumeRounds = 0};
        const test::Rendered flagged = test::render(scene, test::lookingDown(0.4f, 1.8f), settings, {24, 24}, false, unresumed);
        CHECK(flagged.stats.flaggedRays > 0);
        CHECK(image.stats.parkedMarches >= flagged.stats.flaggedRays);
    }
}

TEST_CASE("volumes: Henyey-Greenstein sampling agrees with its evaluation: phase sampling alone equals light sampling alone") {
    // A white slab of optical depth 1 under a downward-facing quad light, seen from below against black. With
    // two interactions per path, light reaching the camera after one scattering event is found either by
    // sampling the phase function until a ray hits the light (LightSampling::BsdfOnly) or by next-event
    // estimation, which evaluates it (LightsOnly); the second event uses next-event estimation in both. The two
    // images agree only if samplePhase draws directions with the density phaseHG reports, for forward and
    // backward scattering alike (the furnace cannot tell: its weight is the albedo whatever the direction).
    test::ValidationGuard guard;
    for (const float g : {-0.5f, 0.5f}) {
        CAPTURE(g);
        core::SceneDescription scene;
        core::Light quad;
        quad.kind = core::Light::Kind::Quad;
        quad.position = {-1.0f, -1.0f, 2.5f};
        quad.edge1 = {0.0f, 2.0f, 0.0f};
        quad.edge2 = {2.0f, 0.0f, 0.0f};  // cross(edge1, edge2) points down, at the slab
        quad.intensity = 2.0f;
        scene.lights.push_back(quad);
        scene.volumes.push_back(boxVolume(2.0f, 1.0f - std::exp(-1.0f), 2.0f, false, glm::vec3(1.0f)));
        core::Camera camera;
        camera.kind = core::Camera::Kind::Orthographic;
        camera.position = {0.0f, 0.0f, -1.0f};
        camera.direction = {0.0f, 0.0f, 1.0f};
        camera.height = 1.8f;
        double means[2], errors[2];
        for (int mode = 0; mode < 2; ++mode) {
            core::RenderSettings settings;
            settings.maxPathLength = 2;
            settings.pixelSamples = 256;
            settings.phaseAnisotropy = g;
            settings.lightSampling = mode == 0 ? core::RenderSettings::LightSampling::BsdfOnly
                                               : core::RenderSettings::LightSampling::LightsOnly;
            const test::Rendered image = test::render(scene, camera, settings, {16, 16});
            const test::Mean m = test::meanRed(image);
            means[mode] = m.mean;
            errors[mode] = m.standardError;
            CHECK(image.stats.flaggedRays == 0);
        }
        MESSAGE("g " << g << ": phase sampling " << means[0] << " +- " << errors[0] << ", light sampling " << means[1]
                     << " +- " << errors[1]);
        CHECK(means[1] > 0.01);
        CHECK(std::abs(means[0] - means[1]) <= 0.01 * means[1] + 4.0 * std::hypot(errors[0], errors[1]));
    }
}

// The majorant grid the device computes (volume_majorants.comp) against a reference computed here from the
// same table: each macrocell's largest table extinction over the range of its voxels (upper planes
// included), raised by the kernel's 1e-5. Odd sizes (partial macrocells), a second volume with nearest
// filtering, a constant field and an empty value range, and a table longer than the default. Also the
// range-maximum table after each transfer-function table, entry by entry against the entries it spans,
// and which volume may be crossed cell by cell (the first: linear, extinction up to 4.6 per unit over
// cells of edge 1; the second is filtered nearest).
TEST_CASE("volumes: the device's majorant grid and the range-maximum tables equal references computed on the host") {
    test::ValidationGuard guard;
    core::SceneDescription description;
    core::Volume a;
    a.dims = {13, 10, 17};
    std::vector<float> values;
    for (uint32_t i = 0; i < a.dims.x * a.dims.y * a.dims.z; ++i) values.push_back(float((i * 2654435761u) % 1000) / 999.0f);
    a.values = std::make_shared<const std::vector<float>>(std::move(values));
    a.valueRange = {0.1f, 0.9f};
    a.colors = {glm::vec3(1.0f)};
    // Spikes between the ends: a kernel that looked at a range's ends alone fails 8 of the 9 cells (tried).
    for (int e = 0; e < 600; ++e) a.opacities.push_back(e % 37 == 18 ? 0.9f : 0.05f * float(e % 5));
    a.unitDistance = 0.5f;
    core::Volume b;
    b.dims = {9, 9, 9};
    b.values = std::make_shared<const std::vector<float>>(9 * 9 * 9, 0.5f);
    b.valueRange = {0.5f, 0.5f};  // empty: every value maps to the first entry
    b.linearFilter = false;
    b.opacities = {0.3f, 0.8f};
    description.volumes = {a, b};
    const core::Scene scene(test::testContext(), description);
    const core::VolumeTable table = core::buildVolumeTable(description.volumes);
    REQUIRE(table.records.size() == 2);
    std::vector<float> device(table.data.size());
    scene.volumeData().download(device.data(), device.size() * sizeof(float));
    size_t compared = 0;
    for (size_t k = 0; k < table.records.size(); ++k) {
        const gpu::VolumeRecord& r = table.records[k];
        const glm::uvec3 dims = description.volumes[k].dims;
        auto extinction = [&](size_t entry) { return table.data[r.tableOffset + 4 * entry + 3]; };
        auto extinctionAt = [&](float position) {
            const size_t i = std::min(size_t(position), size_t(r.tableSize) - 2);
            const float w = position - float(i);
            return extinction(i) * (1.0f - w) + extinction(i + 1) * w;
        };
        const float top = float(r.tableSize - 1), scale = top * r.valueRange.y;
        const glm::uvec3 cells = core::macrocellsPerAxis(dims);
        for (uint32_t mz = 0; mz < cells.z; ++mz)
            for (uint32_t my = 0; my < cells.y; ++my)
                for (uint32_t mx = 0; mx < cells.x; ++mx) {
                    const glm::uvec3 first = glm::uvec3(mx, my, mz) * gpu::VOLUME_MACROCELL;
                    const glm::uvec3 last = glm::min(first + gpu::VOLUME_MACROCELL, dims - 1u);
                    float lowest = 1e30f, highest = -1e30f;
                    for (uint32_t z = first.z; z <= last.z; ++z)
                        for (uint32_t y = first.y; y <= last.y; ++y)
                            for (uint32_t x = first.x; x <= last.x; ++x) {
                                const float value = (*description.volumes[k].values)[(size_t(z) * dims.y + y) * dims.x + x];
                                lowest = std::min(lowest, value);
                                highest = std::max(highest, value);
                            }
                    const float p0 = std::clamp((lowest - r.valueRange.x) * scale, 0.0f, top);
                    const float p1 = std::clamp((highest - r.valueRange.x) * scale, 0.0f, top);
                    float expected = std::max(extinctionAt(p0), extinctionAt(p1));
                    for (size_t e = size_t(std::ceil(p0)); float(e) < p1; ++e) expected = std::max(expected, extinction(e));
                    const size_t cell = (size_t(mz) * cells.y + my) * cells.x + mx;
                    CAPTURE(k);
                    CAPTURE(cell);
                    CHECK(device[r.majorantOffset + cell] == doctest::Approx(expected * (1.0f + 1e-5f)).epsilon(1e-6));
                    ++compared;
                }
        // Level l, entry i: the largest extinction of entries i .. min(i + 2^l, size) - 1.
        size_t wrongMaxima = 0;
        for (uint32_t level = 0; level < core::extinctionMaxLevels(r.tableSize); ++level)
            for (size_t i = 0; i < r.tableSize; ++i) {
                float expected = 0.0f;
                for (size_t e = i; e < std::min(i + (size_t(1) << level), size_t(r.tableSize)); ++e)
                    expected = std::max(expected, extinction(e));
                wrongMaxima += device[r.tableOffset + 4 * r.tableSize + level * r.tableSize + i] != expected;
            }
        CHECK(wrongMaxima == 0);
    }
    // 12 x 9 x 16 cells in 8^3 macrocells, and 8^3 cells in one.
    CHECK(compared == 2 * 2 * 2 + 1);
    CHECK(core::extinctionMaxLevels(600) == 10);  // 2^9 = 512 <= 600 < 1024
    CHECK(scene.report().volumesCellByCell == 1);
}

// A thin shell: the field rises linearly along z over 16 cells and the transfer function is opaque only in
// a band of 17 of its 257 entries around 0.5 (extinction 30 per unit: 1.9 over a cell's depth). Its
// macrocell's majorant is the band's peak over the whole depth, so the scene crosses it cell by cell, where
// each cell's majorant comes from the interpolant's range along the ray; a smooth ramp (extinction 1 per
// unit, 0.125 over the longest cell edge) is not. Through the shell the transmittance is
// exp(-depth * mean extinction), the mean of the table's piecewise-linear extinction over the value
// range; and null collisions stay below twice the real ones (1.12 times measured; 18.5 times with the
// macrocell's majorant alone, tried).
TEST_CASE("volumes: a thin shell is tracked cell by cell, and its transmittance stays exact") {
    test::ValidationGuard guard;
    constexpr uint32_t n = 17;
    core::Volume shell = boxVolume(1.0f, 0.0f, 0.1f, true, glm::vec3(0.0f), n);
    shell.opacities.assign(257, 0.0f);
    for (size_t e = 120; e <= 136; ++e) shell.opacities[e] = 1.0f - std::exp(-3.0f);
    double extinctionSum = 0.0;
    for (const float o : shell.opacities) extinctionSum += -std::log1p(-double(o)) / shell.unitDistance;
    const double expected = std::exp(-extinctionSum / 256.0);  // depth 1; the table's ends are 0

    core::SceneDescription scene;
    scene.volumes.push_back(shell);
    CHECK(core::Scene(test::testContext(), scene).report().volumesCellByCell == 1);
    core::SceneDescription smooth;
    smooth.volumes.push_back(boxVolume(1.0f, 1.0f - std::exp(-1.0f), 1.0f, true, glm::vec3(0.0f), n));
    CHECK(core::Scene(test::testContext(), smooth).report().volumesCellByCell == 0);

    core::RenderSettings settings;
    settings.background = glm::vec4(1.0f);
    settings.maxPathLength = 1;
    settings.pixelSamples = 64;
    const test::Rendered image = test::render(scene, test::lookingDown(2.0f, 1.8f), settings, {32, 32});
    const test::Mean m = test::meanRed(image);
    MESSAGE("shell: transmittance " << m.mean << " +- " << m.standardError << ", expected " << expected << "; null "
                                    << image.stats.nullCollisions << ", real " << image.stats.realCollisions);
    CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
    CHECK(image.stats.flaggedRays == 0);
    CHECK(image.stats.realCollisions > 0);
    CHECK(image.stats.nullCollisions < 2 * image.stats.realCollisions);
}

// Cell by cell where the interpolant along a ray is a true cubic: a 9^3 field of random values, turned about
// an oblique axis so that the camera's vertical rays cross its cells obliquely, seen through a thin shell
// (the table's extinction a tent around 0.5, peak 46 per unit: 11 optical depths over a cell's edge).
// Black medium, white background, one bounce: each sample is 1 where the ray passed, so a pixel's mean is
// the transmittance averaged over its footprint. The reference integrates exp(-integral of extinction)
// on the host over 8 x 8 rays per pixel, 0.002 apart along each ray, through the same table. The image
// mean must agree within 4 standard errors of the sampling noise (each sample a Bernoulli draw) plus
// 0.001, and no 8 x 8 tile may differ by more than 4 of its own standard errors plus 0.005.
TEST_CASE("volumes: cell by cell through a turned random field, transmittance equals a quadrature on the host") {
    test::ValidationGuard guard;
    constexpr uint32_t n = 9;
    core::Volume v;
    v.dims = glm::uvec3(n);
    std::vector<float> values;
    uint32_t state = 12345u;
    for (uint32_t i = 0; i < n * n * n; ++i) {
        state = state * 1664525u + 1013904223u;
        values.push_back(float(state >> 8) / 16777216.0f);
    }
    v.values = std::make_shared<const std::vector<float>>(values);
    v.origin = glm::vec3(-1.0f);
    v.spacing = glm::vec3(2.0f / float(n - 1));
    v.colors = {glm::vec3(0.0f)};
    v.opacities.assign(21, 0.0f);
    v.opacities[10] = 0.9f;
    v.unitDistance = 0.05f;  // peak extinction -ln(0.1) / 0.05 = 46 per unit
    v.transform = glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
    core::SceneDescription scene;
    scene.volumes.push_back(v);
    CHECK(core::Scene(test::testContext(), scene).report().volumesCellByCell == 1);

    // The host's reference: the table as VolumeTable builds it (opacity resampled to 256 entries, then
    // extinction per entry, linear between entries) and the trilinear interpolant in the turned box.
    const size_t entries = core::transferTableSize(v);
    std::vector<double> table(entries);
    for (size_t e = 0; e < entries; ++e) {
        const double x = double(e) / double(entries - 1) * double(v.opacities.size() - 1);
        const size_t i = std::min(size_t(x), v.opacities.size() - 2);
        const double opacity = v.opacities[i] * (1.0 - (x - double(i))) + v.opacities[i + 1] * (x - double(i));
        table[e] = -std::log1p(-opacity) / v.unitDistance;
    }
    const glm::dmat4 worldToGrid = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 / double(v.spacing.x))) *
                                   glm::translate(glm::dmat4(1.0), -glm::dvec3(v.origin)) *
                                   glm::inverse(glm::dmat4(v.transform));
    auto extinction = [&](const glm::dvec3& g) {  // at grid point g, inside the grid
        const glm::uvec3 i0 = glm::min(glm::uvec3(g), glm::uvec3(n - 2));
        const glm::dvec3 w = g - glm::dvec3(i0);
        double value = 0.0;
        for (uint32_t c = 0; c < 8; ++c) {
            const glm::uvec3 corner = i0 + glm::uvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            const double weight = ((c & 1) ? w.x : 1.0 - w.x) * ((c & 2) ? w.y : 1.0 - w.y) * ((c & 4) ? w.z : 1.0 - w.z);
            value += weight * values[(size_t(corner.z) * n + corner.y) * n + corner.x];
        }
        const double p = std::clamp(value, 0.0, 1.0) * double(entries - 1);
        const size_t e = std::min(size_t(p), entries - 2);
        return table[e] * (1.0 - (p - double(e))) + table[e + 1] * (p - double(e));
    };
    constexpr uint32_t size = 32, sub = 8;
    constexpr float view = 4.0f;  // the turned box reaches 1.73 from the centre
    std::vector<double> reference(size * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            double sum = 0.0;
            for (uint32_t sy = 0; sy < sub; ++sy)
                for (uint32_t sx = 0; sx < sub; ++sx) {
                    const glm::vec2 p = test::groundPoint(view, size, x + (sx + 0.5f) / sub, y + (sy + 0.5f) / sub);
                    // The vertical ray z = 1.75 - s in grid space, s in world units down: clipped to the grid box.
                    const glm::dvec3 o = glm::dvec3(worldToGrid * glm::dvec4(p.x, p.y, 1.75, 1.0));
                    const glm::dvec3 d = glm::dvec3(worldToGrid * glm::dvec4(0.0, 0.0, -1.0, 0.0));
                    double enter = 0.0, leave = 3.5;
                    for (int k = 0; k < 3; ++k) {
                        const double a = (0.0 - o[k]) / d[k], b = (double(n - 1) - o[k]) / d[k];
                        enter = std::max(enter, std::min(a, b));
                        leave = std::min(leave, std::max(a, b));
                    }
                    double depth = 0.0;
                    for (double s = std::floor(enter / 0.002) * 0.002; s < leave; s += 0.002) {
                        const double mid = s + 0.001;  // steps of 0.002 from the top, as over the whole ray
                        if (mid > enter && mid < leave) depth += extinction(o + mid * d) * 0.002;
                    }
                    sum += std::exp(-depth);
                }
            reference[y * size + x] = sum / (sub * sub);
        }

    core::RenderSettings settings;
    settings.background = glm::vec4(1.0f);
    settings.maxPathLength = 1;
    settings.pixelSamples = 256;
    const test::Rendered image = test::render(scene, test::lookingDown(3.0f, view), settings, {size, size});
    double difference = 0.0, variance = 0.0, worstTile = 0.0;
    for (uint32_t ty = 0; ty < size / 8; ++ty)
        for (uint32_t tx = 0; tx < size / 8; ++tx) {
            double tileDifference = 0.0, tileVariance = 0.0;
            for (uint32_t y = ty * 8; y < ty * 8 + 8; ++y)
                for (uint32_t x = tx * 8; x < tx * 8 + 8; ++x) {
                    const double expected = reference[y * size + x];
                    tileDifference += image.at(x, y).r - expected;
                    tileVariance += expected * (1.0 - expected) / settings.pixelSamples;
                }
            difference += tileDifference;
            variance += tileVariance;
            // In units of the tile's allowance: 4 standard errors of its mean plus 0.005.
            worstTile = std::max(worstTile, std::abs(tileDifference / 64.0) / (4.0 * std::sqrt(tileVariance) / 64.0 + 0.005));
        }
    const double pixels = double(size * size), meanDifference = difference / pixels;
    const double standardError = std::sqrt(variance) / pixels;
    double referenceMean = 0.0;
    for (double r : reference) referenceMean += r / pixels;
    MESSAGE("turned random field: image mean " << referenceMean + meanDifference << ", quadrature " << referenceMean
                                               << " (s.e. " << standardError << "); worst tile at " << worstTile
                                               << " of its allowance; null " << image.stats.nullCollisions << ", real "
                                               << image.stats.realCollisions);
    CHECK(std::abs(meanDifference) <= 4.0 * standardError + 0.001);
    CHECK(worstTile <= 1.0);
    CHECK(image.stats.flaggedRays == 0);
    CHECK(image.stats.realCollisions > 0);
}

// A transfer-function edit (same voxels, another opacity): the scene built with the previous one as
// `previous` reuses the voxel buffer (no upload) and renders exactly what a scene built from scratch does;
// a new version of the voxels, or none given, is uploaded. Two volumes of one field share one buffer.
TEST_CASE("volumes: a scene rebuilt after a transfer-function edit reuses the voxels and renders as one built anew") {
    test::ValidationGuard guard;
    core::Volume slab = boxVolume(1.0f, 1.0f - std::exp(-1.0f), 1.0f, true, glm::vec3(0.0f), 17);
    slab.voxelIdentity = {7, 1};
    const core::SceneDescription before = litFloorUnder(slab);
    core::SceneDescription edited = before;
    edited.volumes[0].opacities = {0.0f, 0.3f};
    const core::Scene first(test::testContext(), before);
    CHECK(first.report().volumeVoxelsUploaded == 1);
    CHECK(first.report().volumeVoxelsReused == 0);
    const core::Scene rebuilt(test::testContext(), edited, {}, &first);
    CHECK(rebuilt.report().volumeVoxelsUploaded == 0);
    CHECK(rebuilt.report().volumeVoxelsReused == 1);
    const core::Scene fresh(test::testContext(), edited);
    CHECK(fresh.report().volumeVoxelsUploaded == 1);
    CHECK(rebuilt.report().gpuBytes == fresh.report().gpuBytes);
    core::RenderSettings settings;
    settings.maxPathLength = 2;
    settings.pixelSamples = 4;
    const auto image = [&](const core::Scene& scene) {
        core::PathTracer tracer(test::testContext());
        tracer.resize({16, 16}, false);
        tracer.render(scene, test::lookingDown(0.4f, 1.8f), settings);
        std::vector<glm::vec4> color(16 * 16);
        tracer.readColor(core::ColorFormat::Rgba32Float, color.data());
        return color;
    };
    const std::vector<glm::vec4> a = image(rebuilt), b = image(fresh), c = image(first);
    CHECK(a == b);
    CHECK(a != c);  // the edit shows: a thinner medium
    // A new version of the voxels, or no identity, is uploaded again.
    core::SceneDescription changed = edited;
    changed.volumes[0].voxelIdentity.version = 2;
    CHECK(core::Scene(test::testContext(), changed, {}, &rebuilt).report().volumeVoxelsUploaded == 1);
    changed.volumes[0].voxelIdentity = {};
    CHECK(core::Scene(test::testContext(), changed, {}, &rebuilt).report().volumeVoxelsUploaded == 1);
    // One field in two volumes (e.g. two instances): one upload.
    core::SceneDescription twice = before;
    twice.volumes.push_back(twice.volumes[0]);
    twice.volumes[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f));
    const core::Scene shared(test::testContext(), twice);
    CHECK(shared.report().volumesKept == 2);
    CHECK(shared.report().volumeVoxelsUploaded == 1);
    CHECK(shared.report().volumeVoxelsReused == 1);
}
