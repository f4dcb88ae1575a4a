// Time per sample pass of the path tracer at 512x512 on a simple scene (a floor, 20 spheres, a quad
// light, ambient light, paths of up to 5 interactions). A measurement, not a test: it is skipped unless
// asked for, and prints its numbers:
//   ripple_unit_tests -tc="benchmark: path tracer*" --no-skip
#include "core/render/PathTracer.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

using namespace ripple;

TEST_CASE("benchmark: path tracer pass time at 512x512" * doctest::skip()) {
    core::SceneDescription d = test::sceneOf(test::squareMesh(20.0f));
    core::SphereSet balls = test::randomSpheres(20, 71, 2.0f, 0.2f, 0.5f);
    for (glm::vec3& c : balls.centers) c.z = std::abs(c.z) + 0.5f;
    d.sphereSets.push_back(balls);
    d.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f), 1});
    core::Material floor, plastic;
    floor.baseColor = glm::vec3(0.7f);
    plastic.kind = core::Material::Kind::PhysicallyBased;
    plastic.baseColor = {0.8f, 0.3f, 0.2f};
    plastic.metallic = 0.0f;
    plastic.roughness = 0.4f;
    d.materials = {floor, plastic};
    core::Light light;
    light.kind = core::Light::Kind::Quad;
    light.position = {-1.0f, -1.0f, 5.0f};
    light.edge1 = {0.0f, 2.0f, 0.0f};
    light.edge2 = {2.0f, 0.0f, 0.0f};
    light.intensity = 10.0f;
    d.lights.push_back(light);
    core::RenderSettings settings;
    settings.ambientRadiance = 0.3f;
    settings.maxPathLength = 5;
    core::Camera camera;
    camera.position = {0.0f, -7.0f, 4.0f};
    camera.direction = {0.0f, 1.0f, -0.55f};

    core::Scene scene(test::testContext(), d);
    core::PathTracer tracer(test::testContext());
    tracer.resize({512, 512}, false);
    tracer.render(scene, camera, settings);  // warm-up: first-use costs of pipelines and memory
    std::vector<double> seconds;
    core::FrameStats stats;
    for (int pass = 0; pass < 5; ++pass) {
        stats = tracer.render(scene, camera, settings);
        seconds.push_back(stats.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    MESSAGE("512x512, 1 sample per pixel per pass, max path length 5: median " << seconds[2] << " s per pass (min "
            << seconds.front() << ", max " << seconds.back() << "); " << stats.raysTraced << " closest-hit and "
            << stats.shadowRays << " shadow rays per pass on " << test::testContext().deviceName());
    CHECK(stats.nonFiniteSamples == 0);
}
