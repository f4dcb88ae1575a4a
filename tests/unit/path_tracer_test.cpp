// The path tracer against analytic radiance: direct light from directional, point and quad lights on a
// matte plane, furnaces (a convex sphere under ambient light, a closed emitting sphere seen from inside), the
// ambient light at a path's last vertex, background and depth channels, transparency, the non-finite guard,
// and bitwise determinism.
#include "core/render/PathTracer.h"
#include "core/scene/LightTable.h"
#include "tests/support/MixedFrame.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

using namespace ripple;
using test::testContext;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit sphere at the origin of one matte material, and a camera on +z that sees all of it.
core::SceneDescription matteSphere(const glm::vec3& albedo) {
    core::SphereSet sphere;
    sphere.centers = {{0.0f, 0.0f, 0.0f}};
    sphere.radii = {1.0f};
    core::SceneDescription d = test::sceneOf(sphere);
    core::Material m;
    m.baseColor = albedo;
    d.materials.push_back(m);
    return d;
}

core::Camera sphereCamera() {
    core::Camera camera;
    camera.position = {0.0f, 0.0f, 4.0f};
    camera.fovy = 0.7f;
    return camera;
}

core::SceneDescription matteFloor(const glm::vec3& albedo, float side = 200.0f) {
    core::SceneDescription d = test::sceneOf(test::squareMesh(side));
    core::Material m;
    m.baseColor = albedo;
    d.materials.push_back(m);
    return d;
}

// matteFloor with `count` random balls above it (material `ballMaterial`), and a camera looking at them
// from the side: the scene of the tests that images are the same bit for bit however the work is split.
core::SceneDescription ballsOnFloor(uint32_t count, uint32_t seed, uint32_t ballMaterial) {
    core::SceneDescription d = matteFloor(glm::vec3(0.6f, 0.5f, 0.4f));
    core::SphereSet balls = test::randomSpheres(count, seed, 1.0f, 0.1f, 0.3f);
    for (glm::vec3& c : balls.centers) c.z = std::abs(c.z) + 0.3f;
    d.sphereSets.push_back(balls);
    d.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f), ballMaterial});
    return d;
}

core::Camera ballsCamera() {
    core::Camera camera;
    camera.position = {0.0f, -4.0f, 3.0f};
    camera.direction = {0.0f, 1.0f, -0.7f};
    return camera;
}

glm::vec4 meanColor(const test::Rendered& r) {
    glm::dvec4 sum(0.0);
    for (const glm::vec4& c : r.color) sum += glm::dvec4(c);
    return glm::vec4(sum / double(r.color.size()));
}

}  // namespace

// Matte plane (albedo a) under a directional light of irradiance E arriving at theta from the normal,
// direct lighting only: every pixel is a / pi * E * cos(theta), deterministically (one light, no
// randomness reaches the value). Tolerance 1e-5 relative: float rounding of a few operations.
TEST_CASE("path tracer: directional light on a matte plane gives a/pi * E * cos(theta) everywhere") {
    test::ValidationGuard guard;
    const glm::vec3 albedo(0.5f, 0.25f, 0.8f);
    core::SceneDescription d = matteFloor(albedo);
    const float theta = 1.0f, irradiance = 3.0f;
    core::Light light;
    light.kind = core::Light::Kind::Directional;
    light.direction = -glm::vec3(std::sin(theta), 0.0f, std::cos(theta));
    light.intensity = irradiance;
    light.color = {1.0f, 0.5f, 1.0f};
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    const test::Rendered r = test::render(d, test::lookingDown(1.0f, 4.0f), settings);
    const glm::vec3 expected = albedo / float(kPi) * irradiance * light.color * std::cos(theta);
    uint64_t off = 0;
    for (const glm::vec4& c : r.color)
        for (int k = 0; k < 3; ++k) off += std::abs(c[k] - expected[k]) > 1e-5f * expected[k];
    CHECK(off == 0);
    CHECK(r.at(5, 7).r == doctest::Approx(expected.r).epsilon(1e-5));
    CHECK(r.at(5, 7).a == 1.0f);
    CHECK(r.stats.raysTraced == 32 * 32);
    CHECK(r.stats.shadowRays == 32 * 32);
    CHECK(r.stats.nonFiniteSamples == 0);
    CHECK(r.stats.flaggedRays == 0);
}

// A point light of intensity I at height h over the plane: at ground distance rho from its foot,
// L = a / pi * I * cos / d^2 = a / pi * I * h / (rho^2 + h^2)^(3/2). L falls with rho, so each pixel's
// value must lie between L at the farthest and nearest point of its footprint (jitter picks the point),
// within 1e-5 relative for rounding.
TEST_CASE("path tracer: point light over a plane gives a/pi * I * cos / d^2") {
    test::ValidationGuard guard;
    const glm::vec3 albedo(0.7f);
    core::SceneDescription d = matteFloor(albedo);
    const float intensity = 5.0f, h = 1.5f, view = 4.0f;
    core::Light light;
    light.kind = core::Light::Kind::Point;
    light.position = {0.0f, 0.0f, h};
    light.intensity = intensity;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    const uint32_t size = 32;
    const test::Rendered r = test::render(d, test::lookingDown(1.0f, view), settings);
    auto radiance = [&](double rho) { return albedo.x / kPi * intensity * h / std::pow(rho * rho + h * h, 1.5); };
    uint64_t outside = 0;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            const glm::vec2 lo = test::groundPoint(view, size, float(x), float(y));
            const glm::vec2 hi = test::groundPoint(view, size, float(x + 1), float(y + 1));
            const glm::vec2 nearest = glm::clamp(glm::vec2(0.0f), lo, hi);
            const glm::vec2 farthest(std::max(std::abs(lo.x), std::abs(hi.x)), std::max(std::abs(lo.y), std::abs(hi.y)));
            const double value = r.at(x, y).g;
            outside += value > radiance(glm::length(nearest)) * (1 + 1e-5) || value < radiance(glm::length(farthest)) * (1 - 1e-5);
        }
    }
    CHECK(outside == 0);
}

// A square quad light of side s at height h, emitting downward with radiance L, seen from the point
// below its centre: irradiance E = L * sum over the four quadrant rectangles of the classic form factor
// of a rectangle with a corner above the point, F = 1/(2 pi) [a/sqrt(a^2+h^2) atan(b/sqrt(a^2+h^2)) +
// b/sqrt(b^2+h^2) atan(a/sqrt(b^2+h^2))], times pi. The camera views a 1 mm patch there, so the image mean
// estimates a / pi * E over 32x32x32 area samples; cos cos / d^2 over the quad spreads by ~0.6 of its
// mean, so the image mean is within 0.6/sqrt(32768) = 0.33% (1 sigma); tolerance 1.5%.
TEST_CASE("path tracer: quad light by area sampling matches the analytic form factor") {
    test::ValidationGuard guard;
    const glm::vec3 albedo(0.6f);
    core::SceneDescription d = matteFloor(albedo);
    const float side = 2.0f, h = 1.0f, radiance = 2.0f;
    core::Light light;
    light.kind = core::Light::Kind::Quad;
    light.position = {-0.5f * side, -0.5f * side, h};
    light.edge1 = {0.0f, side, 0.0f};  // cross(edge1, edge2) points down, toward the floor
    light.edge2 = {side, 0.0f, 0.0f};
    light.intensity = radiance;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    settings.pixelSamples = 32;
    const test::Rendered r = test::render(d, test::lookingDown(0.5f, 1e-3f), settings);
    const double a = 0.5 * side, b = 0.5 * side;
    const double fa = std::sqrt(a * a + h * h), fb = std::sqrt(b * b + h * h);
    const double quadrant = (a / fa * std::atan(b / fa) + b / fb * std::atan(a / fb)) / (2.0 * kPi);
    const double irradiance = radiance * kPi * 4.0 * quadrant;
    CHECK(meanColor(r).r == doctest::Approx(albedo.x / kPi * irradiance).epsilon(0.015));
    // One-sided: turned to face up, it lights nothing below it.
    std::swap(d.lights[0].edge1, d.lights[0].edge2);
    CHECK(meanColor(test::render(d, test::lookingDown(0.5f, 1e-3f), settings, {8, 8})).r == 0.0f);
}

// White furnace: a white matte sphere under uniform ambient radiance La and nothing else. Each camera
// sample that hits the sphere bounces once, leaves the (convex) sphere and sees La, so a hit sample is
// exactly La (alpha 1); a miss is exactly the background. With one sample per pixel, every pixel is one
// or the other (1e-6 relative), and the hit count matches the sphere's projected disk.
TEST_CASE("path tracer: white furnace with ambient light, exact background elsewhere") {
    test::ValidationGuard guard;
    const core::SceneDescription d = matteSphere(glm::vec3(1.0f));
    core::RenderSettings settings;
    settings.ambientRadiance = 0.7f;
    settings.ambientColor = {1.0f, 0.5f, 0.25f};
    settings.background = {0.1f, 0.2f, 0.3f, 0.4f};
    settings.maxPathLength = 8;
    const test::Rendered r = test::render(d, sphereCamera(), settings);
    const glm::vec3 ambient = settings.ambientColor * settings.ambientRadiance;
    uint64_t hits = 0, other = 0;
    for (const glm::vec4& c : r.color) {
        if (c == settings.background) continue;
        const bool furnace = c.a == 1.0f && std::abs(c.r - ambient.r) <= 1e-6f * ambient.r &&
                             std::abs(c.g - ambient.g) <= 1e-6f * ambient.g && std::abs(c.b - ambient.b) <= 1e-6f * ambient.b;
        (furnace ? hits : other) += 1;
    }
    CHECK(other == 0);
    // Projected disk: half-angle asin(1/4) against the half field of view 0.35 rad: a fraction
    // pi tan^2(asin(1/4)) / (4 tan^2(0.35)) of the image, ~ 147 of 1024 pixels; jitter moves the boundary.
    const double alpha = std::asin(0.25);
    const double expectedHits = kPi * std::tan(alpha) * std::tan(alpha) / (4.0 * std::tan(0.35) * std::tan(0.35)) * 1024.0;
    CHECK(double(hits) == doctest::Approx(expectedHits).epsilon(0.1));
}

// Exact: the ambient light's share of next-event estimation is its power (pi luminance through the scene's
// disc, pi r^2) over the total, 1 without lights and only then, 0 without ambient light.
TEST_CASE("path tracer: the ambient light's share of next-event estimation") {
    const float radius = 2.0f;
    const double ambientPower = kPi * kPi * radius * radius;  // luminance 1
    CHECK(core::ambientLightChance(glm::vec3(1.0f), radius, float(ambientPower)) == doctest::Approx(0.5));
    CHECK(core::ambientLightChance(glm::vec3(1.0f), radius, float(3.0 * ambientPower)) == doctest::Approx(0.25));
    CHECK(core::ambientLightChance(glm::vec3(1.0f), radius, 0.0f) == 1.0f);
    CHECK(core::ambientLightChance(glm::vec3(1.0f), radius, 1e-30f) < 1.0f);
    CHECK(core::ambientLightChance(glm::vec3(0.0f), radius, 1.0f) == 0.0f);
    CHECK(core::ambientLightChance(glm::vec3(0.0f), radius, 0.0f) == 0.0f);
}

// The ambient light at a path's last vertex, by next-event estimation (no BSDF-sampled ray follows it): a
// matte sphere of albedo a under ambient radiance La with maxPathLength 1. Without lights every sample that
// finds the sphere is exactly a La (the cosine-distributed direction cancels the matte BSDF's cosine; 1e-5
// relative). With a sun behind the sphere, which lights none of what the camera sees, next-event estimation
// picks the sun or the ambient light by power, so single samples differ, but the mean over the hit samples
// is still a La: 64 samples per pixel, tolerance 4 standard errors of the measured spread.
TEST_CASE("path tracer: the ambient light reaches a path's last vertex") {
    test::ValidationGuard guard;
    core::SceneDescription d = matteSphere(glm::vec3(0.5f));
    core::RenderSettings settings;
    settings.ambientRadiance = 0.7f;
    settings.background = {0.0f, 0.0f, 0.0f, 0.0f};
    settings.maxPathLength = 1;
    const core::Camera camera = sphereCamera();
    const float expected = 0.5f * settings.ambientRadiance;

    SUBCASE("no lights: every sample exact") {
        const test::Rendered r = test::render(d, camera, settings);
        uint64_t hits = 0, wrong = 0;
        for (const glm::vec4& c : r.color) {
            if (c.a == 0.0f) continue;
            ++hits;
            if (std::abs(c.r - expected) > 1e-5f * expected || std::abs(c.b - expected) > 1e-5f * expected) ++wrong;
        }
        CHECK(hits > 100);
        CHECK(wrong == 0);
    }
    SUBCASE("a sun behind the sphere: the mean") {
        core::Light sun;
        sun.direction = {0.0f, 0.0f, 1.0f};  // travelling toward the camera: it lights the far side only
        sun.intensity = 3.0f;
        d.lights.push_back(sun);
        settings.pixelSamples = 64;
        const test::Rendered r = test::render(d, camera, settings);
        double sum = 0.0, sumSquares = 0.0;
        uint64_t hits = 0;
        for (const glm::vec4& c : r.color) {
            if (c.a != 1.0f) continue;  // pixels wholly on the sphere
            sum += c.r;
            sumSquares += double(c.r) * c.r;
            ++hits;
        }
        REQUIRE(hits > 100);
        const double mean = sum / double(hits);
        const double standardError = std::sqrt(std::max(0.0, sumSquares / double(hits) - mean * mean) / double(hits));
        MESSAGE("mean ", mean, " +- ", standardError, " (expected ", expected, ")");
        CHECK(standardError > 0.0);  // the sun took some of the samples
        CHECK(std::abs(mean - expected) <= 4.0 * standardError + 1e-6);
    }
}

// Closed furnace: the camera inside a sphere whose inside is matte (albedo a) and emits Le. Every
// interaction adds Le times the throughput a^k, so with maxPathLength N the pixel expectation is
// Le (1 - a^N) / (1 - a) (Russian roulette from the third interaction keeps it unbiased but noisy). The
// image mean over 32x32x8 samples has a relative standard error under 0.5%; tolerance 2%. The first
// three interactions are deterministic, so no pixel may be below Le (1 + a + a^2).
TEST_CASE("path tracer: closed emitting sphere seen from inside converges to Le (1 - a^N) / (1 - a)") {
    test::ValidationGuard guard;
    core::SphereSet shell;
    shell.centers = {{0.0f, 0.0f, 0.0f}};
    shell.radii = {5.0f};
    core::SceneDescription d = test::sceneOf(shell);
    core::Material m;
    const float a = 0.5f, emitted = 1.0f;
    m.baseColor = glm::vec3(a);
    m.emissive = glm::vec3(emitted);
    d.materials.push_back(m);
    core::RenderSettings settings;
    settings.maxPathLength = 12;
    settings.pixelSamples = 8;
    core::Camera camera;
    camera.position = {0.5f, -1.0f, 0.25f};
    camera.direction = {0.3f, 1.0f, -0.2f};
    const test::Rendered r = test::render(d, camera, settings);
    const double expected = emitted * (1.0 - std::pow(a, 12)) / (1.0 - a);
    CHECK(meanColor(r).r == doctest::Approx(expected).epsilon(0.02));
    const float floor = emitted * (1.0f + a + a * a) * (1.0f - 1e-5f);
    CHECK(std::all_of(r.color.begin(), r.color.end(), [&](const glm::vec4& c) { return c.r >= floor && c.a == 1.0f; }));
}

// An empty scene shows the background in every pixel, exactly (two samples: sum and halving are exact),
// and the 8-bit formats are the exact rounding of it (within half a step, which allows either neighbour
// only where the exact value is a tie).
TEST_CASE("path tracer: background pixels are exact in every output format") {
    test::ValidationGuard guard;
    core::RenderSettings settings;
    settings.background = {0.2f, 0.6f, 0.9f, 0.3f};
    settings.pixelSamples = 2;
    core::Scene scene(testContext(), core::SceneDescription{});
    core::PathTracer tracer(testContext());
    tracer.resize({16, 8}, true);
    tracer.render(scene, core::Camera{}, settings);
    std::vector<glm::vec4> linear(16 * 8);
    tracer.readColor(core::ColorFormat::Rgba32Float, linear.data());
    CHECK(std::all_of(linear.begin(), linear.end(), [&](const glm::vec4& c) { return c == settings.background; }));
    std::vector<uint8_t> unorm(16 * 8 * 4), srgb(16 * 8 * 4);
    tracer.readColor(core::ColorFormat::Rgba8Unorm, unorm.data());
    tracer.readColor(core::ColorFormat::Rgba8Srgb, srgb.data());
    auto encode = [](double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; };
    for (int k = 0; k < 4; ++k) {
        const double u = settings.background[k] * 255.0;
        const double s = (k < 3 ? encode(settings.background[k]) : settings.background[k]) * 255.0;
        for (size_t p = 0; p < 16 * 8; ++p) {
            CHECK(std::abs(unorm[4 * p + k] - u) <= 0.5 + 1e-3);
            CHECK(std::abs(srgb[4 * p + k] - s) <= 0.5 + 1e-3);
        }
    }
    std::vector<float> depth(16 * 8);
    tracer.readDepth(depth.data());
    CHECK(std::all_of(depth.begin(), depth.end(), [](float z) { return std::isinf(z) && z > 0.0f; }));
    CHECK(tracer.accumulatedSamples() == 2);
}

// Depth = distance along the camera ray to the first hit. Orthographic over the plane z = 0 from z = 3:
// exactly 3. Perspective toward it from z = 2 with fovy 90 degrees: 2 / cos(angle to the axis), which
// within a pixel lies between its values at the footprint's nearest and farthest points (1e-5 relative).
TEST_CASE("path tracer: depth channel equals the analytic distance, +inf on a miss") {
    test::ValidationGuard guard;
    core::SceneDescription d = matteFloor(glm::vec3(0.5f), 10.0f);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    const test::Rendered ortho = test::render(d, test::lookingDown(3.0f, 4.0f), settings, {16, 16}, true);
    CHECK(std::all_of(ortho.depth.begin(), ortho.depth.end(), [](float z) { return std::abs(z - 3.0f) <= 3e-6f; }));

    core::Camera camera;
    camera.position = {0.0f, 0.0f, 2.0f};
    camera.fovy = float(kPi / 2);
    const uint32_t size = 16;
    const test::Rendered persp = test::render(d, camera, settings, {size, size}, true);
    uint64_t outside = 0;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            // Screen offsets in units of the focal length (tan of half the fov = 1): depth = 2 sqrt(1 + |s|^2).
            const glm::vec2 lo = 2.0f * glm::vec2(x, y) / float(size) - 1.0f, hi = 2.0f * glm::vec2(x + 1, y + 1) / float(size) - 1.0f;
            const glm::vec2 nearest = glm::clamp(glm::vec2(0.0f), lo, hi);
            const glm::vec2 farthest = glm::max(glm::abs(lo), glm::abs(hi));
            const double z = persp.depth[y * size + x];
            outside += z < 2.0 * std::sqrt(1.0 + glm::dot(nearest, nearest)) * (1 - 1e-5) ||
                       z > 2.0 * std::sqrt(1.0 + glm::dot(farthest, farthest)) * (1 + 1e-5);
        }
    }
    CHECK(outside == 0);
    camera.direction = {0.0f, 0.0f, 1.0f};  // looking away: every ray misses
    const test::Rendered away = test::render(d, camera, settings, {8, 8}, true);
    CHECK(std::all_of(away.depth.begin(), away.depth.end(), [](float z) { return std::isinf(z); }));
}

// A surface of opacity o that emits 1 in front of a black opaque background: a camera sample sees it
// with probability o, so the mean is o. 32x32x4 samples: standard error sqrt(o (1 - o) / 4096) < 0.008;
// tolerance 0.03.
TEST_CASE("path tracer: opacity passes rays through stochastically") {
    test::ValidationGuard guard;
    core::SceneDescription d = matteFloor(glm::vec3(0.0f));
    d.materials[0].emissive = glm::vec3(1.0f);
    d.materials[0].opacity = 0.3f;
    core::RenderSettings settings;
    settings.background = {0.0f, 0.0f, 0.0f, 1.0f};
    settings.pixelSamples = 4;
    const test::Rendered r = test::render(d, test::lookingDown(1.0f, 2.0f), settings);
    CHECK(meanColor(r).r == doctest::Approx(0.3).epsilon(0.1));
    CHECK(meanColor(r).a == 1.0f);
}

// Radiance that overflows to +inf (an emitter at the float limit plus a light as strong) is counted and
// dropped, never accumulated: the image stays 0 and every sample is reported.
TEST_CASE("path tracer: non-finite samples are counted and dropped") {
    test::ValidationGuard guard;
    core::SceneDescription d = matteFloor(glm::vec3(1.0f));
    d.materials[0].emissive = glm::vec3(3e38f);
    // Emission through a (white) texture: such a surface is not a light, so next-event estimation always
    // picks the directional light and every sample overflows.
    core::Texture white;
    white.width = white.height = 1;
    white.texels = {255, 255, 255, 255};
    d.textures.push_back(white);
    d.materials[0].emissiveTexture = 0;
    core::Light light;
    light.direction = {0.0f, 0.0f, -1.0f};
    light.intensity = 3e38f;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    settings.pixelSamples = 2;
    const test::Rendered r = test::render(d, test::lookingDown(1.0f, 2.0f), settings, {8, 8});
    CHECK(r.stats.nonFiniteSamples == 2 * 64);
    CHECK(std::all_of(r.color.begin(), r.color.end(), [](const glm::vec4& c) { return c == glm::vec4(0.0f); }));
}

// Random numbers are keyed by (pixel, sample, bounce, dimension): the same seed gives the same image bit
// for bit, also when the frame is rendered in many small waves (different queue slots and dispatch
// sizes); another seed gives another image.
TEST_CASE("path tracer: same seed, same image, bit for bit, whatever the wave size") {
    test::ValidationGuard guard;
    core::SceneDescription d = ballsOnFloor(20, 51, 1);
    core::Material metal;
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.roughness = 0.3f;
    d.materials.push_back(metal);
    core::Light light;
    light.kind = core::Light::Kind::Quad;
    light.position = {-1.0f, -1.0f, 3.0f};
    light.edge1 = {0.0f, 2.0f, 0.0f};
    light.edge2 = {2.0f, 0.0f, 0.0f};
    light.intensity = 3.0f;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.ambientRadiance = 0.2f;
    settings.maxPathLength = 6;
    settings.pixelSamples = 2;
    settings.seed = 7;
    const core::Camera camera = ballsCamera();
    const test::Rendered a = test::render(d, camera, settings);
    const test::Rendered b = test::render(d, camera, settings, {32, 32}, false, {.queueCapacity = 100});
    REQUIRE(a.color.size() == b.color.size());
    CHECK(std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec4)) == 0);
    CHECK(a.stats.raysTraced == b.stats.raysTraced);
    CHECK(a.stats.raysTraced > 2 * 32 * 32);
    // a: both samples of the 1,024 pixels in one pass, one wave; b: one sample a pass, in waves of 100.
    CHECK(a.stats.waves == 1);
    CHECK(b.stats.waves == 2 * 11);
    settings.seed = 8;
    const test::Rendered c = test::render(d, camera, settings);
    CHECK(std::memcmp(a.color.data(), c.color.data(), a.color.size() * sizeof(glm::vec4)) != 0);
}

// A frame of few pixels traces several samples of each pixel per pass (PathTracerOptions::packedWavePaths),
// each keyed by its own sample index, and sums them in index order: colour, depth and the surface channels
// (of the frame's last sample) must be those of one sample per pass, bit for bit. Two render() calls of 5
// samples each, packed 5 to a pass (the default on 16x16), 2 to a pass (passes of 2, 2 and 1), and 1.
TEST_CASE("path tracer: several samples of a pixel in one pass give the image of one per pass, bit for bit") {
    test::ValidationGuard guard;
    core::SceneDescription d = ballsOnFloor(12, 5, 0);
    core::Light light;
    light.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    light.intensity = 2.0f;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.ambientRadiance = 0.3f;
    settings.maxPathLength = 4;
    settings.pixelSamples = 5;
    core::Camera camera = ballsCamera();
    camera.apertureRadius = 0.05f;  // the lens sample is keyed by the sample index too
    camera.focusDistance = 4.0f;
    const glm::uvec2 size{16, 16};
    const size_t pixels = size_t(size.x) * size.y;
    using Frame = test::MixedFrame;
    const auto renderTwice = [&](uint32_t packedWavePaths) {
        core::Scene scene(test::testContext(), d);
        core::PathTracer tracer(test::testContext(), {}, {.packedWavePaths = packedWavePaths});
        tracer.resize(size, core::FrameChannels{.depth = true, .albedo = true, .primitiveId = true});
        return test::renderTwiceAndRead(tracer, scene, camera, settings, size);
    };
    const Frame one = renderTwice(1);
    CHECK(one.stats.raysTraced > 5 * pixels);
    CHECK(std::count_if(one.depth.begin(), one.depth.end(), [](float z) { return std::isfinite(z); }) > 0);
    for (const uint32_t packedWavePaths : {uint32_t(2 * pixels), core::PathTracerOptions{}.packedWavePaths}) {
        CAPTURE(packedWavePaths);
        const Frame packed = renderTwice(packedWavePaths);
        CHECK(std::memcmp(one.color.data(), packed.color.data(), pixels * sizeof(glm::vec4)) == 0);
        CHECK(std::memcmp(one.depth.data(), packed.depth.data(), pixels * sizeof(float)) == 0);
        CHECK(one.albedo == packed.albedo);
        CHECK(one.primitiveIds == packed.primitiveIds);
        CHECK(one.stats.raysTraced == packed.stats.raysTraced);
        CHECK(one.stats.shadowRays == packed.stats.shadowRays);
    }
}

// The pixel jitter is stratified over the frames of an accumulation, in two independent sequences (even
// and odd frames; stratified2D in shaders/rng.glsl). A straight edge crosses the image at a slant, and a
// sample's alpha says whether it hit the surface. Against each pixel's exact coverage c, n independent
// samples miss by c (1 - c) / n in variance. Over 64 frames of one sample the RMS error must be far below
// independent sampling's (under 0.6 of it; measured 0.34), each half alone too (0.35),
// and the halves must stay independent: (A - B)^2 / 4 summed over the edge's pixels must match the full
// image's squared error (ratio 0.6 to 1.6; measured 1.05), which is what the error estimate from frames dealt
// into two halves assumes (metrics/ErrorEstimate.h). One Sobol sequence over all frames would fail it:
// its even and odd points fall in opposite halves of the pixel.
TEST_CASE("path tracer: pixel jitter stratifies over frames, in two independent halves") {
    test::ValidationGuard guard;
    const glm::vec2 normal(std::cos(0.3f), std::sin(0.3f)), along(-normal.y, normal.x);
    const float edge = 0.37f;  // the surface covers dot(p, normal) <= edge
    auto point = [&](float s, float inside) { return glm::vec3((edge - inside) * normal + s * along, 0.0f); };
    core::TriangleMesh halfPlane;
    halfPlane.positions = {point(-200.0f, 0.0f), point(200.0f, 0.0f), point(200.0f, 200.0f), point(-200.0f, 200.0f)};
    halfPlane.indices = {{0, 1, 2}, {0, 2, 3}};
    core::SceneDescription d;
    d.meshes.push_back(halfPlane);
    d.instances.push_back({{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f), 0});
    const uint32_t size = 128, frames = 64;
    const core::Camera camera = test::lookingDown(1.0f, float(size));  // pixel (x, y) covers [x - 64, x - 63] x ...
    core::Scene scene(testContext(), d);
    core::PathTracer tracer(testContext());
    tracer.resize({size, size}, false);
    core::RenderSettings settings;
    settings.maxPathLength = 1;
    settings.background = glm::vec4(0.0f);
    settings.pixelSamples = 1;

    // Each frame's sample, from the accumulated mean of alpha after it (hits so far are whole numbers).
    const size_t pixels = size_t(size) * size;
    std::vector<glm::vec4> color(pixels);
    std::vector<int> hitsBefore(pixels, 0), hitsEven(pixels, 0), hitsOdd(pixels, 0);
    for (uint32_t f = 0; f < frames; ++f) {
        tracer.render(scene, camera, settings);
        tracer.readColor(core::ColorFormat::Rgba32Float, color.data());
        for (size_t i = 0; i < pixels; ++i) {
            const int hits = int(std::lround(double(color[i].a) * (f + 1)));
            (f % 2 == 0 ? hitsEven : hitsOdd)[i] += hits - hitsBefore[i];
            hitsBefore[i] = hits;
        }
    }
    double fullError = 0.0, halfError = 0.0, halvesDifference = 0.0, independentFull = 0.0, independentHalf = 0.0;
    uint32_t edgePixels = 0;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            // A pixel whose centre lies farther than its half-diagonal from the edge is wholly on one side.
            const glm::vec2 centre(float(x) - 63.5f, float(y) - 63.5f);
            if (std::abs(glm::dot(centre, normal) - edge) > 0.75f) continue;
            const int grid = 256;  // the pixel's coverage, from a grid of points
            int inside = 0;
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    const glm::vec2 p(float(x) - 64.0f + (i + 0.5f) / grid, float(y) - 64.0f + (j + 0.5f) / grid);
                    inside += glm::dot(p, normal) <= edge ? 1 : 0;
                }
            const double coverage = double(inside) / (grid * grid);
            if (coverage < 0.02 || coverage > 0.98) continue;
            const size_t i = size_t(y) * size + x;
            const double a = hitsEven[i] / (frames / 2.0), b = hitsOdd[i] / (frames / 2.0), full = (a + b) / 2.0;
            fullError += (full - coverage) * (full - coverage);
            halfError += (a - coverage) * (a - coverage) + (b - coverage) * (b - coverage);
            halvesDifference += (a - b) * (a - b) / 4.0;
            independentFull += coverage * (1.0 - coverage) / frames;
            independentHalf += 2.0 * coverage * (1.0 - coverage) / (frames / 2.0);
            ++edgePixels;
        }
    }
    REQUIRE(edgePixels > 100);
    const double full = std::sqrt(fullError / independentFull), half = std::sqrt(halfError / independentHalf);
    const double halvesRatio = halvesDifference / fullError;
    MESSAGE("RMS error over independent sampling's: " << frames << " frames " << full << ", each half " << half
            << "; (A - B)^2 / 4 over the squared error " << halvesRatio << " (" << edgePixels << " pixels)");
    CHECK(full < 0.6);
    CHECK(half < 0.6);
    CHECK(halvesRatio > 0.6);
    CHECK(halvesRatio < 1.6);
}

TEST_CASE("path tracer: bad calls are clear errors") {
    test::ValidationGuard guard;
    core::PathTracer tracer(testContext());
    core::Scene scene(testContext(), core::SceneDescription{});
    CHECK_THROWS_AS(tracer.render(scene, core::Camera{}, core::RenderSettings{}), std::invalid_argument);
    CHECK_THROWS_AS(tracer.resize({0, 4}, false), std::invalid_argument);
    tracer.resize({4, 4}, false);
    float depth[16];
    CHECK_THROWS_AS(tracer.readDepth(depth), std::logic_error);
    core::Camera bad;
    bad.direction = glm::vec3(0.0f);
    CHECK_THROWS_AS(tracer.render(scene, bad, core::RenderSettings{}), std::invalid_argument);
    bad = core::Camera{};
    bad.position.x = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_AS(tracer.render(scene, bad, core::RenderSettings{}), std::invalid_argument);
    std::vector<glm::vec4> color(16);
    CHECK_THROWS_AS(tracer.readColor(static_cast<core::ColorFormat>(9), color.data()), std::invalid_argument);
}
