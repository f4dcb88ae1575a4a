// One scene that touches most of the path tracer (triangles, spheres, a quad light, matte and metal, a
// medium) rendered with its channels on a given context: the tests that compare contexts set up another
// way (discrete-memory mode, lowered limits) with the shared one, bit for bit.
#pragma once

#include "core/render/PathTracer.h"
#include "core/scene/Scene.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"

#include <cmath>
#include <memory>
#include <vector>

namespace ripple::test {

// Balls on a floor under a quad light, a metal and a matte material, and a box of medium whose density
// ramps up (its majorants are read back and refined): every kind of scene buffer.
inline core::SceneDescription mixedScene() {
    core::SceneDescription d = sceneOf(squareMesh(20.0f));
    core::Material floor;
    floor.baseColor = {0.6f, 0.5f, 0.4f};
    core::Material metal;
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.metallic = 1.0f;
    metal.roughness = 0.3f;
    d.materials = {floor, metal};
    core::SphereSet balls = randomSpheres(16, 3, 1.0f, 0.1f, 0.3f);
    for (glm::vec3& c : balls.centers) c.z = std::abs(c.z) + 0.3f;
    d.sphereSets.push_back(balls);
    d.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f), 1});
    core::Light light;
    light.kind = core::Light::Kind::Quad;
    light.position = {-1.0f, -1.0f, 3.0f};
    light.edge1 = {0.0f, 2.0f, 0.0f};
    light.edge2 = {2.0f, 0.0f, 0.0f};
    light.intensity = 3.0f;
    d.lights.push_back(light);
    core::Volume fog;
    const uint32_t n = 9;
    fog.dims = {n, n, n};
    std::vector<float> values;
    for (uint32_t z = 0; z < n; ++z)
        for (uint32_t i = 0; i < n * n; ++i) values.push_back(float(z) / float(n - 1));
    fog.values = std::make_shared<const std::vector<float>>(std::move(values));
    fog.origin = {0.5f, -1.0f, 0.0f};
    fog.spacing = glm::vec3(0.15f);
    fog.valueRange = {0.0f, 1.0f};
    fog.colors = {glm::vec3(0.7f, 0.8f, 0.9f)};
    fog.opacities = {0.0f, 0.6f};
    fog.unitDistance = 0.5f;
    d.volumes.push_back(fog);
    return d;
}

struct MixedFrame {
    std::vector<glm::vec4> color;
    std::vector<float> depth, albedo;
    std::vector<uint32_t> primitiveIds;
    core::FrameStats stats;  // of the second render
};

// Two render() calls on a tracer resized with depth, albedo and primitive ids (the second accumulates onto
// the first), then colour (linear float), depth, albedo and primitive ids read back.
inline MixedFrame renderTwiceAndRead(core::PathTracer& tracer, const core::Scene& scene, const core::Camera& camera,
                                     const core::RenderSettings& settings, glm::uvec2 size) {
    const size_t pixels = size_t(size.x) * size.y;
    MixedFrame f;
    tracer.render(scene, camera, settings);
    f.stats = tracer.render(scene, camera, settings);
    f.color.resize(pixels);
    f.depth.resize(pixels);
    f.albedo.resize(3 * pixels);
    f.primitiveIds.resize(pixels);
    tracer.readColor(core::ColorFormat::Rgba32Float, f.color.data());
    tracer.readDepth(f.depth.data());
    tracer.readChannel(core::SurfaceChannel::Albedo, f.albedo.data());
    tracer.readChannel(core::SurfaceChannel::PrimitiveId, f.primitiveIds.data());
    return f;
}

// mixedScene from the side, rendered twice at 3 samples each and read back (renderTwiceAndRead).
inline MixedFrame renderMixedFrame(const vk::Context& context, core::Traversal traversal, glm::uvec2 size = {32, 24}) {
    core::Scene scene(context, mixedScene(), {}, nullptr, traversal);
    core::PathTracer tracer(context, {.traversal = traversal});
    tracer.resize(size, core::FrameChannels{.depth = true, .albedo = true, .primitiveId = true});
    core::Camera camera;
    camera.position = {0.0f, -4.0f, 3.0f};
    camera.direction = {0.0f, 1.0f, -0.7f};
    camera.aspect = float(size.x) / float(size.y);
    core::RenderSettings settings;
    settings.ambientRadiance = 0.2f;
    settings.maxPathLength = 5;
    settings.pixelSamples = 3;
    return renderTwiceAndRead(tracer, scene, camera, settings, size);
}

}  // namespace ripple::test
