// Discrete-memory mode (vk::ContextOptions::discreteMemory): device buffers are never mapped, every upload and
// download goes through a staging buffer, as on a discrete GPU, and the path tracer renders the image of the
// mapped mode bit for bit.
#include "core/render/PathTracer.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"

#include <doctest/doctest.h>

#include <cstring>
#include <numeric>
#include <vector>

using namespace ripple;

namespace {

// A context of its own in discrete-memory mode, validated like the shared one.
vk::Context& discreteContext() {
    static vk::Context context([] {
        vk::ContextOptions options = test::testContextOptions();
        options.printDeviceChoice = false;
        options.discreteMemory = true;
        return options;
    }());
    return context;
}

std::vector<uint8_t> pattern(size_t bytes, uint32_t seed) {
    std::vector<uint8_t> out(bytes);
    uint32_t x = seed * 2654435761u + 1u;
    for (uint8_t& b : out) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        b = static_cast<uint8_t>(x >> 24);
    }
    return out;
}

// Balls on a floor under a quad light, a metal and a matte material, and a box of medium whose density
// ramps up (its majorants are read back and refined): every kind of scene buffer, and a frame that asks for
// depth, albedo and primitive ids besides the colour.
core::SceneDescription stagedScene() {
    core::SceneDescription d = test::sceneOf(test::squareMesh(20.0f));
    core::Material floor;
    floor.baseColor = {0.6f, 0.5f, 0.4f};
    core::Material metal;
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.metallic = 1.0f;
    metal.roughness = 0.3f;
    d.materials = {floor, metal};
    core::SphereSet balls = test::randomSpheres(16, 3, 1.0f, 0.1f, 0.3f);
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

struct Frame {
    std::vector<glm::vec4> color;
    std::vector<float> depth, albedo;
    std::vector<uint32_t> primitiveIds;
    core::FrameStats stats;
};

Frame renderOn(const vk::Context& context, core::Traversal traversal) {
    const core::SceneDescription d = stagedScene();
    core::Scene scene(context, d, {}, nullptr, traversal);
    core::PathTracer tracer(context, {.traversal = traversal});
    const glm::uvec2 size{32, 24};
    const size_t pixels = size_t(size.x) * size.y;
    tracer.resize(size, core::FrameChannels{.depth = true, .albedo = true, .primitiveId = true});
    core::Camera camera;
    camera.position = {0.0f, -4.0f, 3.0f};
    camera.direction = {0.0f, 1.0f, -0.7f};
    camera.aspect = float(size.x) / float(size.y);
    core::RenderSettings settings;
    settings.ambientRadiance = 0.2f;
    settings.maxPathLength = 5;
    settings.pixelSamples = 3;
    Frame f;
    tracer.render(scene, camera, settings);
    f.stats = tracer.render(scene, camera, settings);  // a second frame accumulates onto the first
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

}  // namespace

// Buffers of sizes around the word and page sizes, written and read at offsets that are not multiples of 4,
// over a background pattern: every byte read back must be the one written there, neighbours untouched.
// Each transfer must have gone through staging (one count each), and only HostStaging buffers are mapped.
TEST_CASE("discrete-memory mode: uploads and downloads go through staging, bit-exactly") {
    vk::Context& context = discreteContext();
    REQUIRE(context.discreteMemoryMode());
    CHECK_FALSE(context.mapsDeviceMemory());
    for (const size_t bytes : {size_t(1), size_t(3), size_t(4), size_t(255), size_t(4096), size_t(65537),
                               size_t((1 << 20) + 7)}) {
        for (const size_t offset : {size_t(0), size_t(1), size_t(13), size_t(4096)}) {
            CAPTURE(bytes);
            CAPTURE(offset);
            const size_t total = offset + bytes + 29;
            vk::Buffer buffer(context, total, "staged test buffer");
            CHECK_FALSE(buffer.isMapped());
            const uint64_t before = context.stagedTransferCount();
            std::vector<uint8_t> expected = pattern(total, uint32_t(bytes + offset));
            buffer.upload(expected.data(), total);
            const std::vector<uint8_t> written = pattern(bytes, uint32_t(7 * bytes + offset + 1));
            buffer.upload(written.data(), bytes, offset);
            std::copy(written.begin(), written.end(), expected.begin() + std::ptrdiff_t(offset));
            std::vector<uint8_t> whole(total), part(bytes);
            buffer.download(whole.data(), total);
            buffer.download(part.data(), bytes, offset);
            CHECK(whole == expected);
            CHECK(part == written);
            CHECK(context.stagedTransferCount() - before == 4);
        }
    }
    vk::Buffer host(context, 64, "host staging test buffer", 0, vk::Buffer::Placement::HostStaging);
    CHECK(host.isMapped());
    const uint64_t before = context.stagedTransferCount();
    const std::vector<uint8_t> bytes = pattern(64, 5);
    std::vector<uint8_t> back(64);
    host.upload(bytes.data(), 64);
    host.download(back.data(), 64);
    CHECK(back == bytes);
    CHECK(context.stagedTransferCount() == before);
    // The shared context maps where the device's memory is host-visible; its transfers are never staged then.
    vk::Buffer mapped(test::testContext(), 64, "mapped test buffer");
    CHECK(mapped.isMapped() == test::testContext().mapsDeviceMemory());
    CHECK(context.validationMessageCount() == 0);
}

// The same scene, camera and settings on the shared context (mapped device memory on a CPU device) and on a
// context in discrete-memory mode: colour, depth, albedo and ids equal bit for bit, with each traversal
// back-end the device has (the ray-query one uploads its acceleration structures' inputs too). The render
// in discrete mode must have staged its transfers (scene, frame constants, read-backs).
TEST_CASE("discrete-memory mode: the path tracer renders the mapped mode's image, bit for bit") {
    test::ValidationGuard guard;
    vk::Context& discrete = discreteContext();
    std::vector<core::Traversal> traversals{core::Traversal::Software};
    if (discrete.supportsRayQuery()) traversals.push_back(core::Traversal::RayQuery);
    for (const core::Traversal traversal : traversals) {
        CAPTURE(core::traversalName(traversal));
        const Frame mapped = renderOn(test::testContext(), traversal);
        const uint64_t before = discrete.stagedTransferCount();
        const Frame staged = renderOn(discrete, traversal);
        CHECK(discrete.stagedTransferCount() - before > 10);
        REQUIRE(mapped.color.size() == staged.color.size());
        CHECK(std::memcmp(mapped.color.data(), staged.color.data(), mapped.color.size() * sizeof(glm::vec4)) == 0);
        CHECK(std::memcmp(mapped.depth.data(), staged.depth.data(), mapped.depth.size() * sizeof(float)) == 0);
        CHECK(std::memcmp(mapped.albedo.data(), staged.albedo.data(), mapped.albedo.size() * sizeof(float)) == 0);
        CHECK(mapped.primitiveIds == staged.primitiveIds);
        CHECK(mapped.stats.raysTraced == staged.stats.raysTraced);
        CHECK(mapped.stats.realCollisions == staged.stats.realCollisions);
        // Not a blank image: the floor, the balls and the medium all show.
        CHECK(mapped.stats.realCollisions > 0);
        const float sum = std::accumulate(mapped.color.begin(), mapped.color.end(), 0.0f,
                                          [](float s, const glm::vec4& c) { return s + c.r + c.g + c.b; });
        CHECK(sum > 0.0f);
    }
    CHECK(discrete.validationMessageCount() == 0);
}
