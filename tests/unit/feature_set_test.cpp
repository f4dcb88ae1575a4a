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
    // The emissive square's triangles are lights too (LIGHT_TRIANGLE).
    CHECK(all.features() == (gpu::FEATURE_TRIANGLES | gpu::FEATURE_SPHERES | gpu::FEATURE_EMISSIVE | gpu::FEATURE_ALPHA |
                             (1u << gpu::FEATURE_LIGHT_SHIFT) | (1u << (gpu::FEATURE_LIGHT_SHIFT + gpu::LIGHT_TRIANGLE))));
    CHECK(core::FeatureSet{all.features()}.describe() == "triangles spheres emissive alpha light:0 light:5");
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
        if (e.kernel == "pt_shade") CHECK(e.features == 0);  // no light kind, matte only
    }
    CHECK(inUse == 4);  // trace_closest, trace_any (or their _rq forms), pt_surface, pt_shade

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

// pt_shade keeps the code of the light kinds and material models a scene has, and the image is the
// unspecialised one bit for bit. Two scenes between them have every light kind but hdri and every material model: a sun
// and a quad light over matte and physically based surfaces; point, spot and ring lights and an emissive
// triangle over a clear-coated and a transmissive material.
TEST_CASE("feature set: pt_shade is built for the scene's light kinds and material models, same image") {
    test::ValidationGuard guard;
    const auto lightOf = [](core::Light::Kind kind, glm::vec3 position) {
        core::Light light;
        light.kind = kind;
        light.position = position;
        light.direction = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f));
        light.edge1 = {0.6f, 0.0f, 0.0f};
        light.edge2 = {0.0f, 0.6f, 0.0f};
        light.intensity = 3.0f;
        light.openingAngle = 2.0f;
        light.radius = 0.4f;
        light.innerRadius = 0.1f;
        light.angularDiameter = kind == core::Light::Kind::Directional ? 0.05f : 0.0f;
        return light;
    };
    core::SceneDescription first = test::sceneOf(test::squareMesh(4.0f));
    first.sphereSets.push_back(core::SphereSet{{{-0.5f, 0.0f, 0.5f}, {0.6f, 0.3f, 0.4f}}, {0.45f, 0.35f}, {}, {}});
    first.instances.push_back(core::InstanceDescription{{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f), 1});
    first.materials.push_back(core::Material{});
    core::Material metal;
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.roughness = 0.4f;
    first.materials.push_back(metal);
    first.lights = {lightOf(core::Light::Kind::Directional, {}), lightOf(core::Light::Kind::Quad, {-0.3f, -0.3f, 2.0f})};

    core::SceneDescription second = first;
    second.materials[1].metallic = 0.0f;
    second.materials[1].clearcoat = 1.0f;
    second.materials[1].clearcoatRoughness = 0.2f;
    second.materials[1].transmission = 0.7f;
    core::TriangleMesh emitter;
    emitter.positions = {{1.5f, -1.5f, 1.0f}, {1.9f, -1.5f, 1.0f}, {1.5f, -1.1f, 1.0f}};
    second.meshes.push_back(emitter);
    second.instances.push_back(core::InstanceDescription{{core::GeometryKind::Triangles, 1}, glm::mat4(1.0f), 2});
    core::Material glow;
    glow.emissive = glm::vec3(4.0f);
    second.materials.push_back(glow);
    second.lights = {lightOf(core::Light::Kind::Point, {0.5f, 0.5f, 2.0f}), lightOf(core::Light::Kind::Spot, {-0.5f, 0.5f, 2.5f}),
                     lightOf(core::Light::Kind::Ring, {0.0f, -0.5f, 2.2f})};

    const auto lightBit = [](uint32_t kind) { return 1u << (gpu::FEATURE_LIGHT_SHIFT + kind); };
    const uint32_t firstShade = lightBit(gpu::LIGHT_DIRECTIONAL) | lightBit(gpu::LIGHT_QUAD) | gpu::FEATURE_PHYSICALLY_BASED;
    const uint32_t secondShade = lightBit(gpu::LIGHT_POINT) | lightBit(gpu::LIGHT_SPOT) | lightBit(gpu::LIGHT_RING) |
                                 lightBit(gpu::LIGHT_TRIANGLE) | gpu::FEATURE_PHYSICALLY_BASED | gpu::FEATURE_CLEARCOAT |
                                 gpu::FEATURE_TRANSMISSION;
    core::RenderSettings settings;
    settings.ambientRadiance = 0.2f;
    settings.pixelSamples = 4;
    core::Camera camera;
    camera.position = {0.0f, -3.0f, 3.0f};
    camera.direction = glm::normalize(glm::vec3(0.0f, 3.0f, -3.0f));
    for (const auto& [description, shadeFeatures] : {std::pair{first, firstShade}, std::pair{second, secondShade}}) {
        CAPTURE(shadeFeatures);
        const core::Scene scene(testContext(), description);
        core::PathTracer specialised(testContext());
        specialised.resize({16, 16}, false);
        specialised.render(scene, camera, settings);
        int shadeVariants = 0;
        for (const core::PipelineCache::Entry& e : specialised.pipelines())
            if (e.inUse && e.kernel == "pt_shade") {
                ++shadeVariants;
                CHECK(e.features == shadeFeatures);
            }
        CHECK(shadeVariants == 1);
        core::PathTracerOptions unspecialisedOptions;
        unspecialisedOptions.specialize = false;
        core::PathTracer unspecialised(testContext(), {}, unspecialisedOptions);
        unspecialised.resize({16, 16}, false);
        const core::FrameStats stats = unspecialised.render(scene, camera, settings);
        CHECK(stats.shadowRays > 0);
        std::vector<glm::vec4> a(256), b(256);
        specialised.readColor(core::ColorFormat::Rgba32Float, a.data());
        unspecialised.readColor(core::ColorFormat::Rgba32Float, b.data());
        double sum = 0.0;
        for (const glm::vec4& c : a) sum += c.r + c.g + c.b;
        CHECK(sum > 0.0);
        CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0);
    }
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
