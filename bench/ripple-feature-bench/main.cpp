// ripple-feature-bench: what leaving out unused features saves. Renders a triangle-only scene and a
// spheres-only scene with kernels specialised for their FeatureSet and with the all-features kernels, and
// prints the time per frame of each (median of --repeat frames, after one warm-up frame that also builds
// the pipelines). Core only: no ANARI, no files.
#include "core/render/PathTracer.h"
#include "core/scene/Scene.h"
#include "core/vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace ripple;

namespace {

// A sphere tessellated into latitude/longitude quads (2 * rings * segments triangles) on a floor.
core::SceneDescription triangleScene() {
    core::TriangleMesh mesh;
    const int rings = 64, segments = 128;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float theta = 3.14159265f * float(r) / rings, phi = 6.2831853f * float(s) / segments;
            mesh.positions.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
            mesh.indices.emplace_back(a, b, a + 1);
            mesh.indices.emplace_back(a + 1, b, b + 1);
        }
    core::SceneDescription scene;
    scene.meshes.push_back(std::move(mesh));
    scene.materials.push_back(core::Material{});
    scene.instances.push_back(core::InstanceDescription{});
    return scene;
}

// A 24 x 24 grid of spheres.
core::SceneDescription sphereScene() {
    core::SphereSet spheres;
    for (int i = 0; i < 24; ++i)
        for (int k = 0; k < 24; ++k) spheres.centers.emplace_back(-1.0f + 2.0f * (i + 0.5f) / 24, -1.0f + 2.0f * (k + 0.5f) / 24, 0.0f);
    spheres.radii = {0.04f};
    core::SceneDescription scene;
    scene.sphereSets.push_back(std::move(spheres));
    scene.materials.push_back(core::Material{});
    core::InstanceDescription instance;
    instance.geometry = {core::GeometryKind::Spheres, 0};
    scene.instances.push_back(instance);
    return scene;
}

double medianFrameMs(const vk::Context& context, const core::Scene& scene, bool specialize, glm::uvec2 size, int repeat) {
    core::PathTracerOptions options;
    options.specialize = specialize;
    core::PathTracer tracer(context, {}, options);
    tracer.resize(size, false);
    core::Camera camera;
    camera.position = {0.0f, 0.0f, 3.0f};
    core::RenderSettings settings;
    settings.ambientRadiance = 1.0f;
    settings.maxPathLength = 3;
    tracer.render(scene, camera, settings);  // warm-up: builds the specialised pipelines
    std::vector<double> ms;
    for (int i = 0; i < repeat; ++i) ms.push_back(1e3 * tracer.render(scene, camera, settings).seconds);
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    glm::uvec2 size{256, 256};
    int repeat = 5;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--size" && i + 1 < argc) {
            size.x = size.y = uint32_t(std::atoi(argv[++i]));
        } else if (arg == "--repeat" && i + 1 < argc) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else {
            std::fprintf(stderr, "usage: ripple-feature-bench [--size N] [--repeat N]\n");
            return arg == "--help" ? 0 : 2;
        }
    }
    try {
        vk::Context context;
        std::printf("ripple-feature-bench: %ux%u, 1 spp, 3 bounces, median of %d frames\n", size.x, size.y, repeat);
        std::printf("%-22s %14s %14s %8s\n", "scene", "specialised ms", "all-features ms", "saved");
        const std::pair<const char*, core::SceneDescription> scenes[] = {{"triangles (16,384)", triangleScene()},
                                                                         {"spheres (576)", sphereScene()}};
        for (const auto& [name, description] : scenes) {
            core::Scene scene(context, description);
            const double special = medianFrameMs(context, scene, true, size, repeat);
            const double all = medianFrameMs(context, scene, false, size, repeat);
            std::printf("%-22s %14.1f %14.1f %7.1f%%\n", name, special, all, 100.0 * (all - special) / all);
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "ripple-feature-bench: %s\n", error.what());
        return 1;
    }
    return 0;
}
