// The FeatureSet of a frame and the pipelines it selects: a triangle-only scene traces and shades with
// kernels specialised for triangles only (no sphere, cylinder, cone or volume variant in use), a scene
// without lights issues no shadow rays, unrequested channels get no buffers, and the specialised image
// equals the all-features one bit for bit.
#include "core/render/PathTracer.h"
#include "shaders/shared/channels.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>

using namespace ripple;
using ripple::test::testContext;

namespace {

core::SceneDescription litSquare(bool withLight) {
    core::SceneDescription scene = test::sceneOf(test::squareMesh(2.0f));
    scene.materials.push_back(core::Material{});
    if (withLight) scene.lights.push_back(core::Light{});  // directional, straight down
    return scene;
}

}  // namespace

TEST_CASE("feature set: what a scene holds") {
    core::Scene triangles(testContext(), litSquare(false));
    CHECK(triangles.features() == gpu::FEATURE_TRIANGLES);
    core::SceneDescription mixed = litSquare(true);
    mixed.sphereSets.push_back(core::SphereSet{{{0, 0, 1}}, {0.5f}, {}, {}});
    mixed.instances.push_back(core::InstanceDescription{{core::GeometryKind::Spheres, 0}});
    mixed.materials[0].emissive = glm::vec3(1.0f);
    mixed.materials[0].opacity = 0.5f;
    core::Scene all(testContext(), mixed);
    CHECK(all.features() == (gpu::FEATURE_TRIANGLES | gpu::FEATURE_SPHERES | gpu::FEATURE_EMISSIVE |
                             gpu::FEATURE_ALPHA | (1u << gpu::FEATURE_LIGHT_SHIFT)));
    CHECK(core::FeatureSet{all.features()}.describe() == "triangles spheres emissive alpha light:0");
    // Any one of a material's six texture slots makes the scene textured: without FEATURE_TEXTURES,
    // pt_surface is built without its texture code.
    for (int slot = 0; slot < 6; ++slot) {
        CAPTURE(slot);
        core::SceneDescription textured = litSquare(false);
        core::Material& m = textured.materials[0];
        int32_t* const slots[] = {&m.baseColorTexture, &m.normalTexture,   &m.metallicTexture,
                                  &m.roughnessTexture, &m.emissiveTexture, &m.opacityTexture};
        *slots[slot] = 0;
        CHECK(core::shadingFeatures(textured) == gpu::FEATURE_TEXTURES);
    }
}

// Exact: the pipelines in use after rendering a triangle-only scene carry no sphere/cylinder/cone/volume
// bit, the only light (the ambient light) costs one shadow ray per camera sample that finds the square (a
// bounce off it escapes), none without it, and the image equals the unspecialised render's bit for bit
// (specialisation removes code, never changes results).
TEST_CASE("feature set: a triangle-only scene runs triangle-only kernels") {
    test::ValidationGuard guard;
    const core::SceneDescription description = litSquare(false);
    core::Scene scene(testContext(), description);
    core::RenderSettings settings;
    settings.ambientRadiance = 1.0f;
    settings.background = {0.0f, 0.0f, 0.0f, 0.0f};  // so that a pixel's alpha is its share of samples on the square
    settings.pixelSamples = 2;
    core::PathTracer specialised(testContext());
    specialised.resize({16, 16}, false);
    const core::FrameStats stats = specialised.render(scene, test::lookingDown(2.0f, 3.0f), settings);
    CHECK(specialised.features().bits == gpu::FEATURE_TRIANGLES);
    std::vector<glm::vec4> a(256), b(256);
    specialised.readColor(core::ColorFormat::Rgba32Float, a.data());
    double squareSamples = 0.0;
    for (const glm::vec4& c : a) squareSamples += double(c.a) * settings.pixelSamples;
    CHECK(squareSamples > 0.0);
    CHECK(double(stats.shadowRays) == squareSamples);
    core::RenderSettings unlit = settings;
    unlit.ambientRadiance = 0.0f;
    CHECK(specialised.render(scene, test::lookingDown(2.0f, 3.0f), unlit).shadowRays == 0);
    const uint32_t unwanted = gpu::FEATURE_SPHERES | gpu::FEATURE_CYLINDERS | gpu::FEATURE_CONES | gpu::FEATURE_VOLUMES |
                              gpu::FEATURE_TEXTURES;
    int inUse = 0;
    for (const core::PipelineCache::Entry& e : specialised.pipelines()) {
        if (!e.inUse) continue;
        ++inUse;
        CAPTURE(e.kernel);
        CHECK((e.features & unwanted) == 0);
        // trace_any_rq under ray-query traversal.
        if (e.kernel.starts_with("trace_any")) CHECK(e.features == gpu::FEATURE_TRIANGLES);
    }
    CHECK(inUse == 3);  // trace_closest, trace_any (or their _rq forms), pt_surface

    core::PathTracerOptions unspecialisedOptions;
    unspecialisedOptions.specialize = false;
    core::PathTracer unspecialised(testContext(), {}, unspecialisedOptions);
    unspecialised.resize({16, 16}, false);
    unspecialised.render(scene, test::lookingDown(2.0f, 3.0f), settings);
    CHECK(unspecialised.features().bits == gpu::FEATURE_ALL);
    unspecialised.readColor(core::ColorFormat::Rgba32Float, b.data());
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0);

    // A second scene with spheres selects another variant; the triangle one stays cached.
    core::SceneDescription spheres = litSquare(false);
    spheres.sphereSets.push_back(core::SphereSet{{{0, 0, 1}}, {0.5f}, {}, {}});
    spheres.instances[0] = core::InstanceDescription{{core::GeometryKind::Spheres, 0}};
    core::Scene sphereScene(testContext(), spheres);
    specialised.render(sphereScene, test::lookingDown(2.0f, 3.0f), settings);
    int cachedTriangleVariants = 0;
    for (const core::PipelineCache::Entry& e : specialised.pipelines())
        if (!e.inUse && e.kernel.starts_with("trace_closest") && e.features == gpu::FEATURE_TRIANGLES)
            ++cachedTriangleVariants;
    CHECK(cachedTriangleVariants == 1);
}

// Exact: the device keeps the pipelines it built (vk::Context::storedPipeline), so a second tracer, as a
// new ANARI frame or the next test render makes one, builds none and renders the same image bit for bit.
TEST_CASE("feature set: a second tracer on the same device builds no pipeline") {
    test::ValidationGuard guard;
    core::Scene scene(testContext(), litSquare(true));
    core::RenderSettings settings;
    settings.pixelSamples = 2;
    std::vector<glm::vec4> first(64), second(64);
    {
        core::PathTracer tracer(testContext());
        tracer.resize({8, 8}, false);
        tracer.render(scene, test::lookingDown(2.0f, 3.0f), settings);
        tracer.readColor(core::ColorFormat::Rgba32Float, first.data());
    }
    const size_t built = testContext().storedPipelineCount();
    CHECK(built >= 3);  // at least the trace, surface and shading kernels
    core::PathTracer tracer(testContext());
    tracer.resize({8, 8}, false);
    tracer.render(scene, test::lookingDown(2.0f, 3.0f), settings);
    tracer.readColor(core::ColorFormat::Rgba32Float, second.data());
    CHECK(testContext().storedPipelineCount() == built);
    CHECK(std::memcmp(first.data(), second.data(), first.size() * sizeof(glm::vec4)) == 0);
}

// Exact byte counts: no optional channel, no bytes; each one asked for adds exactly its buffer.
TEST_CASE("feature set: unrequested channels allocate nothing") {
    core::PathTracer tracer(testContext());
    tracer.resize({8, 4}, core::FrameChannels{});
    CHECK(tracer.channelBytes() == 0);
    CHECK_THROWS_AS(tracer.readChannel(core::SurfaceChannel::Albedo, nullptr), std::logic_error);
    tracer.resize({8, 4}, core::FrameChannels{.objectId = true});
    CHECK(tracer.channelBytes() == 32 * 4 + sizeof(gpu::ChannelBuffers));
    tracer.resize({8, 4}, core::FrameChannels{.depth = true, .albedo = true});
    CHECK(tracer.channelBytes() == 32 * 4 + 32 * 16 + sizeof(gpu::ChannelBuffers));
}
