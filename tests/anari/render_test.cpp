// Render tests of the Ripple device through the public C API: one small scene per geometry, material,
// light and camera subtype compared with a stored reference image, plus checks with exact or analytic
// answers: direct lighting of a matte plane, frame size changes, accumulation, depth, what a change
// rebuilds, and that invalid input beside valid input renders nothing. References: tests/anari/references,
// rewritten by running with RIPPLE_UPDATE_REFERENCES=1 (then look at them before committing).
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>
#include <glm/gtc/constants.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <utility>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

constexpr glm::uvec2 kSize{64, 64};
constexpr int32_t kSamples = 128;
// Reference metric: RMSE over linear RGB of all pixels between 8-bit sRGB images (64x64, 128 samples
// per pixel; 256 for physicallyBased). The random numbers are keyed by pixel and sample, so the same
// build repeats its reference exactly (RMSE 0). The threshold is set from the noise, so that a change of
// sampling alone passes: two independent renders of these scenes (samples 0-127 against 128-255) differ
// by RMSE 0.003 (point light) to 0.014 (image2D, at its high-contrast texel edges), measured with
// lavapipe. At 16 samples they differ by 0.02 (matte), and moving the sphere by 0.05 units gives 0.03.
constexpr double kReferenceRmse = 0.02;

glm::vec3 fromLight() {
    return glm::normalize(glm::vec3(-0.5f, -1.0f, -0.4f));
}

// The stage every reference test shares: a grey floor, a directional light from the upper left unless
// the test brings its own lights, and a perspective camera unless it brings its own.
Image renderStage(RenderSession& s, std::vector<ANARISurface> surfaces, std::vector<ANARILight> lights = {},
                  ANARICamera camera = nullptr, ANARIRenderer renderer = nullptr, glm::uvec2 size = kSize) {
    surfaces.push_back(s.surface(s.floor(), s.matte(glm::vec3(0.7f))));
    if (lights.empty()) lights.push_back(s.directional(fromLight(), 3.0f));
    if (!camera) camera = s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f});
    if (!renderer) renderer = s.renderer(kSamples, 3);
    return s.render(s.frame(s.world(surfaces, lights), camera, renderer, size, ANARI_UFIXED8_RGBA_SRGB));
}

void checkReference(RenderSession& s, const char* name, const Image& image) {
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    CHECK(ripple::test::compareWithReference(name, image, kReferenceRmse) <= kReferenceRmse);
}

ANARIGeometry spheres(RenderSession& s, const std::vector<glm::vec3>& centers, float radius) {
    ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(geometry, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, centers));
    s.set(geometry, "radius", radius);
    s.commit(geometry);
    return geometry;
}

ANARISurface centralSphere(RenderSession& s) {
    return s.surface(spheres(s, {{0.0f, 0.6f, 0.0f}}, 0.6f), s.matte({0.2f, 0.5f, 0.8f}));
}

}  // namespace

TEST_CASE("geometry triangle: indexed with vertex colours, and unindexed with a uniform colour") {
    RenderSession s;
    ANARIGeometry colored = s.keep(anariNewGeometry(s.device, "triangle"));
    s.setObject(
        colored, "vertex.position", ANARI_ARRAY1D,
        s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1.2f, 0.1f, 0}, {0.4f, 0.1f, 0}, {-0.4f, 1.5f, 0}}));
    s.setObject(colored, "vertex.color", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}}));
    s.setObject(colored, "primitive.index", ANARI_ARRAY1D,
                s.array(ANARI_UINT32_VEC3, std::vector<glm::uvec3>{{0, 1, 2}}));
    s.commit(colored);
    ANARIGeometry plain = s.keep(anariNewGeometry(s.device, "triangle"));
    s.setObject(plain, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3,
                        std::vector<glm::vec3>{{0.3f, 0.0f, -0.8f}, {1.3f, 0.0f, 0.2f}, {0.8f, 1.2f, -0.3f}}));
    s.set(plain, "color", glm::vec4(0.9f, 0.8f, 0.2f, 1.0f));
    s.commit(plain);
    ANARIMaterial fromColor = s.matteFromAttribute();
    checkReference(s, "geometry_triangle",
                   renderStage(s, {s.surface(colored, fromColor), s.surface(plain, fromColor)}));
}

TEST_CASE("geometry quad: indexed quads with per-quad colours") {
    RenderSession s;
    ANARIGeometry quads = s.keep(anariNewGeometry(s.device, "quad"));
    const std::vector<glm::vec3> positions = {{-1.4f, 0.0f, 0.0f}, {-0.2f, 0.0f, 0.0f}, {-0.2f, 1.2f, 0.0f},
                                              {-1.4f, 1.2f, 0.0f}, {0.2f, 0.0f, -0.5f}, {1.3f, 0.0f, 0.3f},
                                              {1.3f, 0.9f, 0.3f},  {0.2f, 0.9f, -0.5f}};
    s.setObject(quads, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, positions));
    s.setObject(quads, "primitive.index", ANARI_ARRAY1D,
                s.array(ANARI_UINT32_VEC4, std::vector<glm::uvec4>{{0, 1, 2, 3}, {4, 5, 6, 7}}));
    s.setObject(quads, "primitive.color", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>{{0.9f, 0.3f, 0.2f, 1}, {0.2f, 0.8f, 0.3f, 1}}));
    s.commit(quads);
    checkReference(s, "geometry_quad", renderStage(s, {s.surface(quads, s.matteFromAttribute())}));
}

TEST_CASE("geometry sphere: per-vertex radii and colours") {
    RenderSession s;
    ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(
        geometry, "vertex.position", ANARI_ARRAY1D,
        s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1.1f, 0.3f, 0}, {0, 0.5f, -0.3f}, {1.0f, 0.7f, 0.2f}}));
    s.setObject(geometry, "vertex.radius", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{0.3f, 0.5f, 0.7f}));
    s.setObject(geometry, "vertex.color", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3,
                        std::vector<glm::vec3>{{0.9f, 0.2f, 0.2f}, {0.2f, 0.9f, 0.2f}, {0.2f, 0.2f, 0.9f}}));
    s.commit(geometry);
    checkReference(s, "geometry_sphere", renderStage(s, {s.surface(geometry, s.matteFromAttribute())}));
}

// Attribute arrays longer than the vertices or primitives need are read up to what is needed, as helide does
// and the SDK's CTS expects (its curve and cylinder cases size per-primitive arrays for the vertices);
// shorter ones are an error naming the array, and the geometry renders nothing.
TEST_CASE("geometry attribute arrays: longer than needed is read in part, shorter is an error") {
    for (const size_t colours : {size_t(3), size_t(1)}) {
        CAPTURE(colours);
        RenderSession s;
        ANARIGeometry geometry = spheres(s, {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}}, 0.4f);
        const std::vector<glm::vec3> palette{{0.9f, 0.1f, 0.1f}, {0.1f, 0.9f, 0.1f}, {0.1f, 0.1f, 0.9f}};
        s.setObject(geometry, "vertex.color", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>(palette.begin(), palette.begin() + long(colours))));
        s.commit(geometry);
        ANARICamera camera = s.orthographic(glm::vec3(0, 0, 3), glm::vec3(0, 0, -1));
        ANARIRenderer renderer = s.renderer(4, 2, glm::vec4(0.0f));  // the ambient light needs a bounce
        s.set(renderer, "ambientRadiance", 1.0f);
        s.commit(renderer);
        const Image image = s.render(s.frame(s.world({s.surface(geometry, s.matteFromAttribute())}, {}), camera,
                                             renderer, {16, 8}, ANARI_FLOAT32_VEC4));
        if (colours == 3) {
            CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
            CHECK(image.at(3, 4).r > 4.0f * image.at(3, 4).g);   // left sphere: the first colour, red
            CHECK(image.at(12, 4).g > 4.0f * image.at(12, 4).r); // right sphere: the second, green
        } else {
            CHECK_MESSAGE(s.log.count({"'vertex.color' has 1 elements, needs 2"}) == 1, s.log.dump());
            for (const glm::vec4& p : image.linear) CHECK(p.r == 0.0f);  // nothing rendered
        }
    }
}

TEST_CASE("geometry cylinder: indexed, per-cylinder radii, capped") {
    RenderSession s;
    ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "cylinder"));
    s.setObject(
        geometry, "vertex.position", ANARI_ARRAY1D,
        s.array(ANARI_FLOAT32_VEC3,
                std::vector<glm::vec3>{{-1.2f, 0.2f, 0}, {1.2f, 0.2f, 0}, {-0.6f, 0, -0.6f}, {-0.6f, 1.4f, -0.6f}}));
    s.setObject(geometry, "primitive.index", ANARI_ARRAY1D,
                s.array(ANARI_UINT32_VEC2, std::vector<glm::uvec2>{{0, 1}, {2, 3}}));
    s.setObject(geometry, "primitive.radius", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{0.2f, 0.35f}));
    s.set(geometry, "caps", "both");
    s.commit(geometry);
    checkReference(s, "geometry_cylinder", renderStage(s, {s.surface(geometry, s.matte({0.9f, 0.5f, 0.1f}))}));
}

TEST_CASE("material matte") {
    RenderSession s;
    checkReference(s, "material_matte", renderStage(s, {centralSphere(s)}));
}

TEST_CASE("material physicallyBased: metals and a dielectric of different roughness, under ambient light") {
    RenderSession s;
    auto pbr = [&](glm::vec3 baseColor, float metallic, float roughness) {
        ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
        s.set(material, "baseColor", baseColor);
        s.set(material, "metallic", metallic);
        s.set(material, "roughness", roughness);
        s.commit(material);
        return material;
    };
    std::vector<ANARISurface> surfaces = {
        s.surface(spheres(s, {{-1.1f, 0.5f, 0}}, 0.5f), pbr({1.0f, 0.8f, 0.3f}, 1.0f, 0.5f)),
        s.surface(spheres(s, {{0.0f, 0.5f, 0}}, 0.5f), pbr({0.8f, 0.1f, 0.1f}, 0.0f, 0.5f)),
        s.surface(spheres(s, {{1.1f, 0.5f, 0}}, 0.5f), pbr({0.9f, 0.9f, 0.9f}, 1.0f, 0.8f)),
    };
    // Light reflected by glossy metal onto the floor is the noisiest path here: twice the samples.
    ANARIRenderer renderer = s.renderer(2 * kSamples, 3);
    s.set(renderer, "ambientRadiance", 0.4f);
    s.commit(renderer);
    checkReference(s, "material_physically_based", renderStage(s, surfaces, {}, nullptr, renderer));
}

TEST_CASE("material with an image2D sampler: a checkerboard on a quad") {
    RenderSession s;
    ANARIGeometry quad = s.keep(anariNewGeometry(s.device, "quad"));
    s.setObject(
        quad, "vertex.position", ANARI_ARRAY1D,
        s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, 0.1f, 0}, {1, 0.1f, 0}, {1, 1.5f, 0}, {-1, 1.5f, 0}}));
    s.setObject(quad, "vertex.attribute0", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC2, std::vector<glm::vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    s.commit(quad);

    // 4x4 texels: red and white squares, with one blue texel at (u, v) = (0, 0) to show orientation.
    std::vector<uint8_t> texels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const bool red = (x + y) % 2 == 0;
            const bool corner = x == 0 && y == 0;
            texels.insert(texels.end(), {uint8_t(corner ? 20 : 230), uint8_t(red || corner ? 20 : 230),
                                         uint8_t(red && !corner ? 20 : 230), 255});
        }
    ANARIArray2D image = s.keep(anariNewArray2D(s.device, nullptr, nullptr, nullptr, ANARI_UFIXED8_RGBA_SRGB, 4, 4));
    std::memcpy(anariMapArray(s.device, image), texels.data(), texels.size());
    anariUnmapArray(s.device, image);
    ANARISampler sampler = s.keep(anariNewSampler(s.device, "image2D"));
    s.setObject(sampler, "image", ANARI_ARRAY2D, image);
    s.set(sampler, "filter", "nearest");
    s.commit(sampler);
    ANARIMaterial material = s.keep(anariNewMaterial(s.device, "matte"));
    s.setObject(material, "color", ANARI_SAMPLER, sampler);
    s.commit(material);
    checkReference(s, "material_image2d", renderStage(s, {s.surface(quad, material)}));
}

TEST_CASE("light directional") {
    RenderSession s;
    ANARILight light = s.keep(anariNewLight(s.device, "directional"));
    s.set(light, "direction", glm::vec3(0.6f, -1.0f, -0.3f));
    s.set(light, "irradiance", 2.5f);
    s.set(light, "color", glm::vec3(1.0f, 0.85f, 0.6f));
    s.commit(light);
    checkReference(s, "light_directional", renderStage(s, {centralSphere(s)}, {light}));
}

TEST_CASE("light point") {
    RenderSession s;
    ANARILight light = s.keep(anariNewLight(s.device, "point"));
    s.set(light, "position", glm::vec3(1.0f, 2.0f, 1.2f));
    s.set(light, "intensity", 6.0f);
    s.commit(light);
    checkReference(s, "light_point", renderStage(s, {centralSphere(s)}, {light}));
}

TEST_CASE("light quad: a panel above the sphere, emitting downwards") {
    RenderSession s;
    ANARILight light = s.keep(anariNewLight(s.device, "quad"));
    s.set(light, "position", glm::vec3(-0.5f, 2.2f, -0.5f));
    s.set(light, "edge1", glm::vec3(1, 0, 0));
    s.set(light, "edge2", glm::vec3(0, 0, 1));  // edge1 x edge2 = -y: the front faces down
    s.set(light, "radiance", 4.0f);
    s.commit(light);
    checkReference(s, "light_quad", renderStage(s, {centralSphere(s)}, {light}));
}

TEST_CASE("camera perspective: wide frame (aspect from the frame size), narrow field of view") {
    RenderSession s;
    ANARICamera camera = s.perspective({2.0f, 1.0f, 3.0f}, {0.0f, 0.5f, 0.0f});
    s.set(camera, "fovy", 0.6f);
    s.commit(camera);
    checkReference(s, "camera_perspective", renderStage(s, {centralSphere(s)}, {}, camera, nullptr, {80, 48}));
}

TEST_CASE("camera orthographic") {
    RenderSession s;
    ANARICamera camera = s.keep(anariNewCamera(s.device, "orthographic"));
    s.set(camera, "position", glm::vec3(2.0f, 2.0f, 3.0f));
    s.set(camera, "direction", glm::vec3(-2.0f, -1.5f, -3.0f));
    s.set(camera, "up", glm::vec3(0, 1, 0));
    s.set(camera, "height", 3.0f);
    s.commit(camera);
    checkReference(s, "camera_orthographic", renderStage(s, {centralSphere(s)}, {}, camera));
}

TEST_CASE("direct lighting of a matte plane matches a / pi * E * cos(theta)") {
    // Orthographic view straight down on a plane of albedo a, lit by a directional light of irradiance E at
    // theta from the normal; paths end at the first surface (maxPathLength 1). A delta light sampled
    // directly has no variance, so every pixel is exact up to float rounding: tolerance 0.1% relative.
    RenderSession s;
    const float albedo = 0.5f, irradiance = 2.0f, theta = glm::radians(60.0f);
    ANARILight light = s.directional({std::sin(theta), -std::cos(theta), 0.0f}, irradiance);
    ANARISurface plane = s.surface(s.floor(), s.matte(glm::vec3(albedo)));
    ANARICamera camera = s.keep(anariNewCamera(s.device, "orthographic"));
    s.set(camera, "position", glm::vec3(0, 5, 0));
    s.set(camera, "direction", glm::vec3(0, -1, 0));
    s.set(camera, "up", glm::vec3(0, 0, -1));
    s.set(camera, "height", 4.0f);  // inside the 6-wide floor: every pixel sees the plane
    s.commit(camera);
    ANARIRenderer renderer = s.renderer(1, 1, {0, 0, 0, 1});
    const Image image = s.render(s.frame(s.world({plane}, {light}), camera, renderer, {16, 16}, ANARI_FLOAT32_VEC4));

    const float expected = albedo / glm::pi<float>() * irradiance * std::cos(theta);
    int wrong = 0;
    for (const glm::vec4& pixel : image.linear)
        for (int c = 0; c < 3; ++c) wrong += std::abs(pixel[c] - expected) > 1e-3f * expected ? 1 : 0;
    CHECK_MESSAGE(wrong == 0, "centre pixel " << image.at(8, 8).x << ", expected " << expected);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("a world with no light and no emitter, ambientRadiance unset: an implicit white ambient light of 1") {
    // Orthographic view straight down on an unoccluded matte plane of albedo a under a uniform sky of
    // radiance L: every pixel is a * L. With L = 1 (the implicit light) and 64 samples of one bounce the
    // mean over the image is within 1% of a; with ambientRadiance set to 0 (explicitly) it is black.
    auto render = [](bool setAmbientToZero, bool addLight, RenderSession& s) {
        ANARISurface plane = s.surface(s.floor(), s.matte(glm::vec3(0.5f)));
        ANARICamera camera = s.keep(anariNewCamera(s.device, "orthographic"));
        s.set(camera, "position", glm::vec3(0, 5, 0));
        s.set(camera, "direction", glm::vec3(0, -1, 0));
        s.set(camera, "up", glm::vec3(0, 0, -1));
        s.set(camera, "height", 4.0f);
        s.commit(camera);
        ANARIRenderer renderer = s.renderer(64, 2, {0, 0, 0, 1});
        if (setAmbientToZero) {
            s.set(renderer, "ambientRadiance", 0.0f);
            s.commit(renderer);
        }
        std::vector<ANARILight> lights;
        if (addLight) lights.push_back(s.directional({0, -1, 0}, 0.001f));
        const Image image = s.render(s.frame(s.world({plane}, lights), camera, renderer, {16, 16}, ANARI_FLOAT32_VEC4));
        double mean = 0.0;
        for (const glm::vec4& pixel : image.linear) mean += (pixel.r + pixel.g + pixel.b) / 3.0;
        return mean / double(image.linear.size());
    };
    {
        RenderSession s;
        CHECK(render(false, false, s) == doctest::Approx(0.5).epsilon(0.01));
        CHECK_MESSAGE(s.log.entries.size() == 1, s.log.dump());
        CHECK(s.log.count({}) == 0);  // reported as information, not as a warning
        CHECK(s.log.find("implicit white ambient light of radiance 1") == 0);
    }
    {
        RenderSession s;
        CHECK(render(true, false, s) == 0.0);
        CHECK(s.log.find("implicit") == -1);
    }
    {
        RenderSession s;  // a light turns the implicit one off: a / pi * E = 1.6e-4
        CHECK(render(false, true, s) == doctest::Approx(0.5 / glm::pi<double>() * 0.001).epsilon(0.01));
        CHECK(s.log.find("implicit") == -1);
    }
}

TEST_CASE("frames accumulate while nothing changes and start over on a change") {
    RenderSession s;
    ANARICamera camera = s.perspective({0, 1.6f, 4}, {0, 0.5f, 0});
    ANARIRenderer renderer = s.renderer(2, 2);
    ANARIFrame frame = s.frame(s.world({centralSphere(s)}, {s.directional(fromLight(), 2)}), camera, renderer, {16, 16},
                               ANARI_FLOAT32_VEC4);
    s.render(frame);
    CHECK(s.numSamples(frame) == 2);
    s.render(frame);
    s.render(frame);
    CHECK(s.numSamples(frame) == 6);
    CHECK(s.sceneBuilds(frame) == 1);

    s.set(camera, "position", glm::vec3(0.3f, 1.6f, 4.0f));  // a camera-only change: no scene rebuild
    s.commit(camera);
    s.render(frame);
    CHECK(s.numSamples(frame) == 2);
    CHECK(s.sceneBuilds(frame) == 1);

    s.setInt(renderer, "pixelSamples", 3);
    s.commit(renderer);
    s.render(frame);
    CHECK(s.numSamples(frame) == 3);

    // KHR_FRAME_ACCUMULATION: with "accumulation" off, every render starts over.
    const int32_t off = 0;
    s.setRaw(frame, "accumulation", ANARI_BOOL, &off);
    s.commit(frame);
    s.render(frame);
    s.render(frame);
    CHECK(s.numSamples(frame) == 3);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("a material change rebuilds the scene but reuses the unchanged geometry's BVH") {
    RenderSession s;
    ANARIMaterial material = s.matte({0.8f, 0.2f, 0.2f});
    ANARISurface sphere = s.surface(spheres(s, {{0, 0.5f, 0}}, 0.5f), material);
    ANARIFrame frame =
        s.frame(s.world({sphere}, {s.directional(fromLight(), 2)}), s.perspective({0, 1.6f, 4}, {0, 0.5f, 0}),
                s.renderer(1, 2), {16, 16}, ANARI_FLOAT32_VEC4);
    s.render(frame);
    s.set(material, "color", glm::vec3(0.2f, 0.8f, 0.2f));
    s.commit(material);
    s.render(frame);
    CHECK(s.sceneBuilds(frame) == 2);
    uint64_t built = 99, reused = 0;
    CHECK(anariGetProperty(s.device, frame, "ripple.blasBuilt", ANARI_UINT64, &built, sizeof(built), ANARI_WAIT) == 1);
    CHECK(anariGetProperty(s.device, frame, "ripple.blasReused", ANARI_UINT64, &reused, sizeof(reused), ANARI_WAIT) ==
          1);
    CHECK(built == 0);
    CHECK(reused == 1);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("changing the frame size renders at the new size and starts the accumulation over") {
    RenderSession s;
    ANARIFrame frame =
        s.frame(s.world({centralSphere(s)}, {s.directional(fromLight(), 2)}), s.perspective({0, 1.6f, 4}, {0, 0.5f, 0}),
                s.renderer(2, 2), {32, 32}, ANARI_UFIXED8_RGBA_SRGB);
    const Image before = s.render(frame);
    CHECK(before.width == 32);
    s.render(frame);
    CHECK(s.numSamples(frame) == 4);

    s.set(frame, "size", glm::uvec2(24, 40));
    s.commit(frame);
    const Image after = s.render(frame);
    CHECK(after.width == 24);
    CHECK(after.height == 40);
    CHECK(after.linear.size() == 24u * 40u);
    CHECK(s.numSamples(frame) == 2);
    // The sphere is still in the middle: the centre pixel is lit, not background.
    CHECK(after.at(12, 20).z > 0.05f);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("depth channel: distance to the first hit, +inf where nothing is hit") {
    // Orthographic camera 5 units above a plane that covers the left half of the view only.
    RenderSession s;
    ANARIGeometry half = s.keep(anariNewGeometry(s.device, "quad"));
    s.setObject(half, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-2, 0, 2}, {0, 0, 2}, {0, 0, -2}, {-2, 0, -2}}));
    s.commit(half);
    ANARICamera camera = s.keep(anariNewCamera(s.device, "orthographic"));
    s.set(camera, "position", glm::vec3(0, 5, 0));
    s.set(camera, "direction", glm::vec3(0, -1, 0));
    s.set(camera, "up", glm::vec3(0, 0, -1));
    s.set(camera, "height", 2.0f);
    s.commit(camera);
    const Image image = s.render(s.frame(s.world({s.surface(half, s.matte(glm::vec3(0.5f)))}, {}), camera,
                                         s.renderer(1, 1), {16, 16}, ANARI_FLOAT32_VEC4, true));
    REQUIRE(image.depth.size() == 256u);
    for (uint32_t y = 0; y < 16; ++y) {
        CHECK(image.depth[y * 16 + 2] == doctest::Approx(5.0f).epsilon(1e-5));  // left: the plane
        CHECK(std::isinf(image.depth[y * 16 + 13]));                            // right: nothing
    }
    CHECK(s.log.problems() == 0);
}

// Clip planes: two planes fill the view of a camera 5 units above the lower one and 3 above the upper one;
// "near" and "far" are distances along the view direction (planes for both kinds of camera), so the depth
// channel shows which plane each setting leaves. The perspective camera looks at them through a narrow
// field of view, its pixels' rays within 1% of the axis's length.
TEST_CASE("camera near and far: clip planes along the view direction, perspective and orthographic") {
    RenderSession s;
    const auto plane = [&](float y) {
        ANARIGeometry quad = s.keep(anariNewGeometry(s.device, "quad"));
        s.setObject(quad, "vertex.position", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-9, y, 9}, {9, y, 9}, {9, y, -9}, {-9, y, -9}}));
        s.commit(quad);
        return s.surface(quad, s.matte(glm::vec3(0.5f)));
    };
    ANARIWorld world = s.world({plane(0.0f), plane(2.0f)}, {});
    constexpr float kInf = std::numeric_limits<float>::infinity();
    for (const char* subtype : {"orthographic", "perspective"}) {
        CAPTURE(subtype);
        ANARICamera camera = s.keep(anariNewCamera(s.device, subtype));
        s.set(camera, "position", glm::vec3(0, 5, 0));
        s.set(camera, "direction", glm::vec3(0, -1, 0));
        s.set(camera, "up", glm::vec3(0, 0, -1));
        if (std::string(subtype) == "perspective") s.set(camera, "fovy", 0.2f);
        for (const auto& [nearClip, farClip, expected] :
             std::vector<std::tuple<float, float, float>>{{0.0f, kInf, 3.0f},   // defaults: the upper plane
                                                          {4.0f, kInf, 5.0f},   // the upper one clipped
                                                          {0.0f, 4.0f, 3.0f},   // far behind it
                                                          {1.0f, 2.5f, kInf},   // both beyond far
                                                          {3.5f, 4.5f, kInf}}) {// between the two
            CAPTURE(nearClip);
            CAPTURE(farClip);
            s.set(camera, "near", nearClip);
            if (std::isinf(farClip)) anariUnsetParameter(s.device, camera, "far");
            else s.set(camera, "far", farClip);
            s.commit(camera);
            const Image image = s.render(s.frame(world, camera, s.renderer(1, 1), {8, 8}, ANARI_FLOAT32_VEC4, true));
            REQUIRE(image.depth.size() == 64u);
            for (const float depth : image.depth) {
                if (std::isinf(expected)) CHECK(std::isinf(depth));
                else CHECK(depth == doctest::Approx(expected).epsilon(0.01));
            }
        }
    }
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    // far not beyond near is refused with a warning naming it, and nothing is clipped.
    ANARICamera bad = s.keep(anariNewCamera(s.device, "orthographic"));
    s.set(bad, "position", glm::vec3(0, 5, 0));
    s.set(bad, "direction", glm::vec3(0, -1, 0));
    s.set(bad, "up", glm::vec3(0, 0, -1));
    s.set(bad, "near", 4.0f);
    s.set(bad, "far", 1.0f);
    s.commit(bad);
    const Image image = s.render(s.frame(world, bad, s.renderer(1, 1), {8, 8}, ANARI_FLOAT32_VEC4, true));
    CHECK(s.log.count({"parameter 'far' must be greater than 'near'"}) == 1);
    CHECK(image.depth[27] == doctest::Approx(5.0f).epsilon(0.01));  // near 4 kept (the upper plane clipped), far dropped
}

TEST_CASE("invalid geometry beside valid geometry renders nothing: the image is unchanged") {
    RenderSession s;
    ANARICamera camera = s.perspective({0, 1.6f, 4}, {0, 0.5f, 0});
    ANARIRenderer renderer = s.renderer(2, 2);
    ANARILight light = s.directional(fromLight(), 2);
    ANARISurface valid = centralSphere(s);
    const Image alone = s.render(s.frame(s.world({valid}, {light}), camera, renderer, {24, 24}, ANARI_FLOAT32_VEC4));
    CHECK(s.log.problems() == 0);

    const float nan = std::numeric_limits<float>::quiet_NaN();
    ANARIGeometry notFinite = s.keep(anariNewGeometry(s.device, "triangle"));
    s.setObject(notFinite, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, 0, 1}, {1, 0, 1}, {0, nan, 1}}));
    s.commit(notFinite);
    ANARIGeometry outOfRange = s.keep(anariNewGeometry(s.device, "triangle"));
    s.setObject(outOfRange, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, 0, 1}, {1, 0, 1}, {0, 1, 1}}));
    s.setObject(outOfRange, "primitive.index", ANARI_ARRAY1D,
                s.array(ANARI_UINT32_VEC3, std::vector<glm::uvec3>{{0, 1, 7}}));
    s.commit(outOfRange);
    ANARIGeometry noPositions = s.keep(anariNewGeometry(s.device, "sphere"));
    s.commit(noPositions);
    ANARIGeometry unknown = s.keep(anariNewGeometry(s.device, "teapot"));
    s.commit(unknown);
    ANARIMaterial material = s.matte(glm::vec3(0.9f));
    std::vector<ANARISurface> surfaces = {valid};
    for (ANARIGeometry bad : {notFinite, outOfRange, noPositions, unknown})
        surfaces.push_back(s.surface(bad, material));
    const Image mixed = s.render(s.frame(s.world(surfaces, {light}), camera, renderer, {24, 24}, ANARI_FLOAT32_VEC4));

    CHECK(ripple::test::rmseRgb(alone, mixed) == 0.0);
    // Nothing but invalid surfaces: the background, everywhere.
    surfaces.erase(surfaces.begin());
    const Image onlyBad = s.render(s.frame(s.world(surfaces, {light}), camera, renderer, {8, 8}, ANARI_FLOAT32_VEC4));
    for (const glm::vec4& pixel : onlyBad.linear) CHECK(pixel == glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    CHECK_MESSAGE(s.log.count({"vertex.position", "not finite"}) == 1, s.log.dump());
    CHECK(s.log.count({"primitive.index", "7"}) == 1);
    CHECK(s.log.count({"missing required parameter 'vertex.position'"}) == 1);
    CHECK(s.log.count({"unknown geometry subtype 'teapot'"}) == 1);
}

TEST_CASE("renderFrame returns before the frame is done; anariFrameReady(NO_WAIT) turns 1 eventually") {
    RenderSession s;
    // A frame long enough that a render on the calling thread would show in the time anariRenderFrame takes
    // to return. The first render also starts Vulkan and builds the scene and pipelines (partly on the
    // calling thread); the second, which adds samples to the first, is the one timed.
    ANARIFrame frame =
        s.frame(s.world({centralSphere(s)}, {s.directional(fromLight(), 2)}), s.perspective({0, 1.6f, 4}, {0, 0.5f, 0}),
                s.renderer(64, 3), {64, 64}, ANARI_UFIXED8_VEC4);
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    const auto start = std::chrono::steady_clock::now();
    anariRenderFrame(s.device, frame);
    const double returned = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int readyAtOnce = anariFrameReady(s.device, frame, ANARI_NO_WAIT);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (anariFrameReady(s.device, frame, ANARI_NO_WAIT) == 0 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    CHECK(anariFrameReady(s.device, frame, ANARI_NO_WAIT) == 1);
    float duration = -1.0f;
    CHECK(anariGetProperty(s.device, frame, "duration", ANARI_FLOAT32, &duration, sizeof(duration), ANARI_WAIT) == 1);
    CHECK(duration > 0.0f);
    CHECK(readyAtOnce == 0);
    CHECK(returned < 0.25 * double(duration));
    float raysPerSecond = -1.0f;
    CHECK(anariGetProperty(s.device, frame, "ripple.raysPerSecond", ANARI_FLOAT32, &raysPerSecond,
                           sizeof(raysPerSecond), ANARI_WAIT) == 1);
    CHECK(raysPerSecond > 0.0f);
    MESSAGE("64x64, 64 samples, paths of 3: " << duration << " s (returned after " << returned << " s), "
                                               << raysPerSecond / 1e6f << " Mrays/s");
    // GPU time per stage: the stages a lit surface scene runs took time, one it has no use for took none,
    // and together they fit in the frame's duration.
    const auto stage = [&](const char* name) {
        uint64_t microseconds = ~0ull;
        const std::string property = std::string("ripple.stageMicroseconds.") + name;
        REQUIRE(anariGetProperty(s.device, frame, property.c_str(), ANARI_UINT64, &microseconds, sizeof microseconds,
                                 ANARI_WAIT) == 1);
        return microseconds;
    };
    uint64_t total = 0;
    for (const char* name : {"generate", "traceClosest", "surface", "shade", "traceAny", "shadowResolve", "accumulate"}) {
        CAPTURE(name);
        CHECK(stage(name) > 0);
        total += stage(name);
    }
    CHECK(stage("volume") == 0);
    CHECK(double(total) * 1e-6 <= double(duration));
    uint64_t unknown = 0;
    CHECK(anariGetProperty(s.device, frame, "ripple.stageMicroseconds.teapot", ANARI_UINT64, &unknown, sizeof unknown,
                           ANARI_WAIT) == 0);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("every subtype the device lists is created without the unknown-subtype warning") {
    RenderSession s;
    const std::pair<ANARIDataType, const char*> types[] = {
        {ANARI_GEOMETRY, "geometry"}, {ANARI_MATERIAL, "material"}, {ANARI_SAMPLER, "sampler"},  {ANARI_LIGHT, "light"},
        {ANARI_CAMERA, "camera"},     {ANARI_INSTANCE, "instance"}, {ANARI_RENDERER, "renderer"}};
    int listed = 0;
    for (const auto& [type, word] : types) {
        const char** subtypes = anariGetObjectSubtypes(s.device, type);
        REQUIRE(subtypes);
        for (; *subtypes; ++subtypes, ++listed) {
            ANARIObject object = anariNewObject(s.device, word, *subtypes);
            CHECK(object);
            anariRelease(s.device, object);
        }
    }
    CHECK(listed == 26);  // 14 + cone, curve, isosurface, omnidirectional + spot, ring, hdri + image1D, image3D, transform,
                         // primitive + the eyeLight renderer
    CHECK_MESSAGE(s.log.count({"unknown"}) == 0, s.log.dump());
}

TEST_CASE("an instance moves its group's surfaces and lights; world bounds follow") {
    // The same sphere and point light, once placed by an instance translated by (0.8, 0, -0.5), once
    // given at the translated positions directly. The random numbers are the same, so at most float
    // rounding of the transformed hits may differ: RMSE over linear RGB below 0.002 (measured: 0).
    const glm::vec3 offset(0.8f, 0.0f, -0.5f);
    auto pointLight = [](RenderSession& s, glm::vec3 position) {
        ANARILight light = s.keep(anariNewLight(s.device, "point"));
        s.set(light, "position", position);
        s.set(light, "intensity", 5.0f);
        s.commit(light);
        return light;
    };
    RenderSession s;
    ANARICamera camera = s.perspective({0, 1.6f, 4}, {0, 0.5f, 0});
    ANARIRenderer renderer = s.renderer(4, 2);
    ANARISurface floor = s.surface(s.floor(), s.matte(glm::vec3(0.7f)));
    ANARIMaterial blue = s.matte({0.2f, 0.5f, 0.8f});

    ANARIGroup group = s.keep(anariNewGroup(s.device));
    s.setObject(group, "surface", ANARI_ARRAY1D,
                s.objects(ANARI_SURFACE, {s.surface(spheres(s, {{0, 0.6f, 0}}, 0.6f), blue)}));
    s.setObject(group, "light", ANARI_ARRAY1D, s.objects(ANARI_LIGHT, {pointLight(s, {0.5f, 2.0f, 0.5f})}));
    s.commit(group);
    ANARIInstance instance = s.keep(anariNewInstance(s.device, "transform"));
    s.setObject(instance, "group", ANARI_GROUP, group);
    const glm::mat4 transform = glm::mat4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, offset.x, offset.y, offset.z, 1);
    s.setRaw(instance, "transform", ANARI_FLOAT32_MAT4, &transform);
    s.commit(instance);
    ANARIWorld instanced = s.world({floor}, {});
    s.setObject(instanced, "instance", ANARI_ARRAY1D, s.objects(ANARI_INSTANCE, {instance}));
    s.commit(instanced);
    const Image viaInstance = s.render(s.frame(instanced, camera, renderer, {32, 32}, ANARI_FLOAT32_VEC4));

    ANARIWorld direct = s.world({floor, s.surface(spheres(s, {glm::vec3(0, 0.6f, 0) + offset}, 0.6f), blue)},
                                {pointLight(s, glm::vec3(0.5f, 2.0f, 0.5f) + offset)});
    const Image placed = s.render(s.frame(direct, camera, renderer, {32, 32}, ANARI_FLOAT32_VEC4));
    CHECK(ripple::test::rmseRgb(viaInstance, placed) < 0.002);

    // Bounds: the floor (+-3 at y = 0) and the moved sphere (top at y = 1.2).
    float bounds[6] = {};
    REQUIRE(anariGetProperty(s.device, instanced, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof(bounds), ANARI_WAIT) ==
            1);
    const float expected[6] = {-3, 0, -3, 3, 1.2f, 3};
    for (int i = 0; i < 6; ++i) CHECK(bounds[i] == doctest::Approx(expected[i]).epsilon(1e-6));
    CHECK(s.log.problems() == 0);
}

TEST_CASE("rewriting a committed geometry's array moves it at the next frame, without a recommit") {
    RenderSession s;
    ANARICamera camera = s.perspective({0, 1.6f, 4}, {0, 0.5f, 0});
    ANARIRenderer renderer = s.renderer(2, 2);
    ANARILight light = s.directional(fromLight(), 2);
    ANARIArray1D centers = s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-0.8f, 0.5f, 0}});
    ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(sphere, "vertex.position", ANARI_ARRAY1D, centers);
    s.set(sphere, "radius", 0.5f);
    s.commit(sphere);
    ANARIMaterial material = s.matte(glm::vec3(0.8f));
    ANARIFrame frame =
        s.frame(s.world({s.surface(sphere, material)}, {light}), camera, renderer, {24, 24}, ANARI_FLOAT32_VEC4);
    const Image before = s.render(frame);

    const glm::vec3 moved(0.8f, 0.5f, 0.0f);
    std::memcpy(anariMapArray(s.device, centers), &moved, sizeof(moved));
    anariUnmapArray(s.device, centers);
    const Image after = s.render(frame);
    CHECK(s.sceneBuilds(frame) == 2);
    CHECK(s.numSamples(frame) == 2);

    const Image fresh = s.render(s.frame(s.world({s.surface(spheres(s, {moved}, 0.5f), material)}, {light}), camera,
                                         renderer, {24, 24}, ANARI_FLOAT32_VEC4));
    CHECK(ripple::test::rmseRgb(after, fresh) == 0.0);
    CHECK(ripple::test::rmseRgb(before, after) > 0.01);
    CHECK(s.log.problems() == 0);
}

TEST_CASE("a frame missing its camera reports an error, is ready at once and maps nothing") {
    RenderSession s;
    ANARIFrame frame = s.keep(anariNewFrame(s.device));
    s.setObject(frame, "world", ANARI_WORLD, s.world({centralSphere(s)}, {}));
    s.setObject(frame, "renderer", ANARI_RENDERER, s.renderer(1, 1));
    s.set(frame, "size", glm::uvec2(8, 8));
    const ANARIDataType colorType = ANARI_UFIXED8_VEC4;
    s.setRaw(frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    s.commit(frame);
    anariRenderFrame(s.device, frame);
    CHECK(anariFrameReady(s.device, frame, ANARI_WAIT) == 1);
    uint32_t width = 1, height = 1;
    ANARIDataType type = ANARI_FLOAT32;
    CHECK(anariMapFrame(s.device, frame, "channel.color", &width, &height, &type) == nullptr);
    CHECK(width == 0);
    CHECK_MESSAGE(s.log.count({"cannot render", "camera"}) == 1, s.log.dump());
}

TEST_CASE("bad parameters are reported, naming object and parameter, and the frame still renders") {
    RenderSession s;
    ANARICamera camera = s.perspective({0, 1.6f, 4}, {0, 0.5f, 0});
    s.set(camera, "fovy", 7.0f);  // beyond pi: the default is used
    s.commit(camera);
    ANARIRenderer renderer = s.renderer(1, 2);
    s.setInt(renderer, "pixelSamples", -3);
    s.commit(renderer);

    ANARISampler sampler = s.keep(anariNewSampler(s.device, "image2D"));
    s.setObject(sampler, "image", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>(4)));  // not 2D
    s.commit(sampler);
    ANARIMaterial textured = s.keep(anariNewMaterial(s.device, "matte"));
    s.setObject(textured, "color", ANARI_SAMPLER, sampler);
    s.commit(textured);

    ANARIGroup group = s.keep(anariNewGroup(s.device));
    s.setObject(group, "surface", ANARI_ARRAY1D, s.objects(ANARI_SURFACE, {s.surface(s.floor(), textured)}));
    s.commit(group);
    ANARIInstance singular = s.keep(anariNewInstance(s.device, "transform"));
    s.setObject(singular, "group", ANARI_GROUP, group);
    const glm::mat4 flat(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1));
    s.setRaw(singular, "transform", ANARI_FLOAT32_MAT4, &flat);
    s.commit(singular);
    ANARILight light = s.keep(anariNewLight(s.device, "directional"));
    s.set(light, "direction", glm::vec3(0.0f));
    s.commit(light);

    ANARIWorld world = s.world({centralSphere(s)}, {light});
    s.setObject(world, "instance", ANARI_ARRAY1D, s.objects(ANARI_INSTANCE, {singular}));
    s.commit(world);
    const Image image = s.render(s.frame(world, camera, renderer, {16, 16}, ANARI_FLOAT32_VEC4));
    CHECK(image.linear.size() == 256u);
    CHECK(s.numSamples(s.frame(world, camera, renderer, {16, 16}, ANARI_FLOAT32_VEC4)) == 0);  // never rendered

    CHECK_MESSAGE(s.log.count({"perspective", "fovy"}) == 1, s.log.dump());
    CHECK(s.log.count({"renderer", "pixelSamples"}) == 1);
    CHECK(s.log.count({"image2D", "'image'"}) >= 1);
    CHECK(s.log.count({"transform", "invertible"}) == 1);
    CHECK(s.log.count({"directional", "direction"}) == 1);
}
