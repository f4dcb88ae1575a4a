// Small scenes and a one-call render for the path tracer suites: a square plane, orthographic and
// perspective cameras, and render() returning linear RGBA (Rgba32Float), depth and the frame statistics.
#pragma once

#include "core/render/PathTracer.h"
#include "core/scene/Scene.h"
#include "tests/support/TestContext.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace ripple::test {

struct Rendered {
    glm::uvec2 size{0, 0};
    std::vector<glm::vec4> color;  // linear RGBA, row 0 at the bottom
    std::vector<float> depth;      // empty unless asked for
    core::FrameStats stats;
    const glm::vec4& at(uint32_t x, uint32_t y) const { return color[size_t(y) * size.x + x]; }
};

inline Rendered render(const core::SceneDescription& description, const core::Camera& camera,
                       const core::RenderSettings& settings, glm::uvec2 size = {32, 32}, bool wantDepth = false,
                       const core::PathTracerOptions& options = {}) {
    core::Scene scene(testContext(), description);
    core::PathTracer tracer(testContext(), {}, options);
    tracer.resize(size, wantDepth);
    Rendered out;
    out.size = size;
    out.stats = tracer.render(scene, camera, settings);
    out.color.resize(size_t(size.x) * size.y);
    tracer.readColor(core::ColorFormat::Rgba32Float, out.color.data());
    if (wantDepth) {
        out.depth.resize(out.color.size());
        tracer.readDepth(out.depth.data());
    }
    return out;
}

// A square in the plane z = 0, centred on the origin, with side `side`, facing +z; two triangles
// (0,1,2) and (0,2,3) over the corners (-,-), (+,-), (+,+), (-,+), texcoords 0..1 across it.
inline core::TriangleMesh squareMesh(float side) {
    const float h = 0.5f * side;
    core::TriangleMesh mesh;
    mesh.positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
    mesh.indices = {{0, 1, 2}, {0, 2, 3}};
    mesh.texcoords = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    return mesh;
}

// Orthographic camera at height z above the origin looking down -z, +y up on screen, `height` world
// units tall (square images).
inline core::Camera lookingDown(float z, float height) {
    core::Camera camera;
    camera.kind = core::Camera::Kind::Orthographic;
    camera.position = {0.0f, 0.0f, z};
    camera.direction = {0.0f, 0.0f, -1.0f};
    camera.up = {0.0f, 1.0f, 0.0f};
    camera.height = height;
    return camera;
}

// World point seen through the centre of pixel (x, y) + offset (in pixels) by lookingDown(z, height) on
// a size x size image.
inline glm::vec2 groundPoint(float height, uint32_t size, float x, float y) {
    return glm::vec2((x / float(size) - 0.5f) * height, (y / float(size) - 0.5f) * height);
}

// The red channel's mean and its standard error over the pixels [x0, x1) x [y0, y1) of `image` (block
// xyzw; all of it by default); NaN for both when one of them is not finite.
struct Mean {
    double mean = 0.0;
    double standardError = 0.0;
};

inline Mean meanRed(const Rendered& image, glm::uvec4 block = glm::uvec4(0u, ~0u, 0u, ~0u)) {
    double sum = 0.0, sumSquares = 0.0, n = 0.0;
    for (uint32_t y = block.z; y < std::min(block.w, image.size.y); ++y)
        for (uint32_t x = block.x; x < std::min(block.y, image.size.x); ++x) {
            const double r = image.at(x, y).r;
            if (!std::isfinite(r)) return {NAN, NAN};
            sum += r;
            sumSquares += r * r;
            n += 1.0;
        }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sumSquares / n - mean * mean) / n)};
}

// `image` against `reference` in square blocks of `side` pixels: per block, the difference of their red means
// over its tolerance, 1% of the reference's mean plus 4 standard errors of the difference. Returns the largest
// such ratio (NaN for a NaN mean): every block agrees when it is at most 1.
inline double worstBlock(const Rendered& image, const Rendered& reference, uint32_t side) {
    double worst = 0.0;
    for (uint32_t y = 0; y < reference.size.y; y += side)
        for (uint32_t x = 0; x < reference.size.x; x += side) {
            const glm::uvec4 block(x, x + side, y, y + side);
            const Mean a = meanRed(image, block), b = meanRed(reference, block);
            if (std::isnan(a.mean) || std::isnan(b.mean)) return NAN;
            const double difference = std::abs(a.mean - b.mean);
            if (difference > 0.0) worst = std::max(worst, difference / (0.01 * b.mean + 4.0 * std::hypot(a.standardError, b.standardError)));
        }
    return worst;
}

// `volume` alone under a sun of irradiance 3 from (0.3, -0.2, -1): the lit scenes of the volume tests.
inline core::SceneDescription sunlitVolume(const core::Volume& volume) {
    core::SceneDescription scene;
    core::Light sun;
    sun.kind = core::Light::Kind::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    scene.volumes.push_back(volume);
    return scene;
}

}  // namespace ripple::test
