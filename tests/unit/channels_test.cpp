// The albedo, normal and id channels from the first visible hit, and the cameras that make the rays:
// omnidirectional (equirectangular) directions and the thin lens of depth of field.
#include "core/render/PathTracer.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace ripple;
using ripple::test::testContext;

namespace {

// Two instances of a quad-split square (trianglesPerPrimitive 2) side by side at z = 0, with object and
// instance ids, seen from above; the right half of the image sees instance 1.
core::SceneDescription twoSquares() {
    core::TriangleMesh mesh = test::squareMesh(1.0f);
    mesh.trianglesPerPrimitive = 2;  // one application quad
    core::SceneDescription scene = test::sceneOf(mesh);
    core::Material red;
    red.baseColor = {0.8f, 0.1f, 0.2f};
    scene.materials = {core::Material{}, red};
    scene.instances[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.0f, 0.0f));
    scene.instances[0].objectId = 7;
    scene.instances[0].instanceId = 70;
    core::InstanceDescription right = scene.instances[0];
    right.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.0f, 0.0f));
    right.materialIndex = 1;
    right.objectId = 8;
    right.instanceId = 80;
    scene.instances.push_back(right);
    return scene;
}

}  // namespace

// Exact ids, and albedo/normal to 1e-6: pixels over the left square report quad 0 (both triangles),
// object 7, instance 70, the default grey; the right square 0/8/80 and red; the normal is +z everywhere;
// pixels beyond the squares (the top rows) report ~0u and zero vectors.
TEST_CASE("channels: albedo, normal and ids of the first hit") {
    test::ValidationGuard guard;
    core::Scene scene(testContext(), twoSquares());
    core::PathTracer tracer(testContext());
    const glm::uvec2 size{16, 16};
    tracer.resize(size, core::FrameChannels{.albedo = true, .normal = true, .primitiveId = true, .objectId = true,
                                            .instanceId = true});
    // 2 world units tall: the squares cover y in [-0.5, 0.5], rows 4..11.
    tracer.render(scene, test::lookingDown(2.0f, 2.0f), core::RenderSettings{});
    const size_t pixels = size_t(size.x) * size.y;
    std::vector<float> albedo(3 * pixels), normal(3 * pixels);
    std::vector<uint32_t> prim(pixels), object(pixels), instance(pixels);
    tracer.readChannel(core::SurfaceChannel::Albedo, albedo.data());
    tracer.readChannel(core::SurfaceChannel::Normal, normal.data());
    tracer.readChannel(core::SurfaceChannel::PrimitiveId, prim.data());
    tracer.readChannel(core::SurfaceChannel::ObjectId, object.data());
    tracer.readChannel(core::SurfaceChannel::InstanceId, instance.data());
    auto at = [&](uint32_t x, uint32_t y) { return size_t(y) * size.x + x; };
    for (uint32_t y : {5u, 10u}) {
        for (uint32_t x : {2u, 6u, 9u, 13u}) {
            const size_t i = at(x, y);
            const bool right = x >= 8;
            CAPTURE(x);
            CAPTURE(y);
            CHECK(prim[i] == 0);
            CHECK(object[i] == (right ? 8u : 7u));
            CHECK(instance[i] == (right ? 80u : 70u));
            CHECK(albedo[3 * i] == doctest::Approx(right ? 0.8 : 0.8).epsilon(1e-6));
            CHECK(albedo[3 * i + 1] == doctest::Approx(right ? 0.1 : 0.8).epsilon(1e-6));
            CHECK(normal[3 * i + 2] == doctest::Approx(1.0).epsilon(1e-6));
        }
    }
    const size_t miss = at(3, 15);
    CHECK(prim[miss] == ~0u);
    CHECK(object[miss] == ~0u);
    CHECK(instance[miss] == ~0u);
    CHECK(albedo[3 * miss] == 0.0f);
    CHECK(normal[3 * miss + 2] == 0.0f);
}

// Equirectangular: the pixel at the image centre looks along `direction`; a quarter of the width to the
// right looks along `right`; the top row looks up. Checked with depth to 1e-4: a unit-distance square
// placed in each of those directions is found at distance 1.
TEST_CASE("camera: omnidirectional directions") {
    test::ValidationGuard guard;
    core::SceneDescription scene;
    core::TriangleMesh wall = test::squareMesh(0.5f);
    scene.meshes.push_back(wall);
    auto place = [&](const glm::mat4& m) {
        core::InstanceDescription instance;
        instance.transform = m;
        scene.instances.push_back(instance);
    };
    // Camera at the origin looking along -z with +y up: right is +x.
    place(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -1)));                                            // ahead
    place(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)), 1.5707963f, glm::vec3(0, 1, 0)));  // right
    place(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)), 1.5707963f, glm::vec3(1, 0, 0)));  // up
    core::Camera camera;
    camera.kind = core::Camera::Kind::Omnidirectional;
    const test::Rendered r = test::render(scene, camera, core::RenderSettings{}, {64, 32}, true);
    auto depthAt = [&](uint32_t x, uint32_t y) { return r.depth[size_t(y) * 64 + x]; };
    CHECK(depthAt(32, 16) == doctest::Approx(1.0).epsilon(2e-2));  // pixel centres jitter by up to 1/64 turn
    CHECK(depthAt(48, 16) == doctest::Approx(1.0).epsilon(2e-2));
    CHECK(depthAt(32, 31) == doctest::Approx(1.0).epsilon(2e-2));
    CHECK(std::isinf(depthAt(0, 16)));  // behind: nothing there
}

// Thin lens: with a large aperture, a checker-free test of focus: a square at the focus distance keeps a
// sharp edge (pixel fully in or out), one far off focus is blurred (edge pixels partly covered). Alpha
// (coverage of the background) over 32 samples: in focus every pixel is 0 or 1 within 1e-6 away from
// the edge column; out of focus some pixel within 3 columns of the edge is in (0.1, 0.9).
TEST_CASE("camera: depth of field keeps the focus plane sharp") {
    test::ValidationGuard guard;
    core::SceneDescription scene = test::sceneOf(test::squareMesh(2.0f));
    scene.instances[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));  // edge at x = 0
    core::Camera camera;
    camera.position = {0.0f, 0.0f, 4.0f};
    camera.fovy = 0.5f;
    camera.apertureRadius = 0.3f;
    core::RenderSettings settings;
    settings.background = glm::vec4(0.0f);
    settings.pixelSamples = 32;
    settings.maxPathLength = 1;
    auto edgeBlur = [&](float focus) {
        camera.focusDistance = focus;
        const test::Rendered r = test::render(scene, camera, settings, {32, 8});
        int partial = 0;
        for (uint32_t x = 12; x < 20; ++x) {
            if (x == 15 || x == 16) continue;  // the edge column itself is partly covered even in focus
            const float a = r.at(x, 4).a;
            partial += (a > 0.1f && a < 0.9f) ? 1 : 0;
        }
        return partial;
    };
    CHECK(edgeBlur(4.0f) == 0);
    CHECK(edgeBlur(1.0f) > 0);
}
