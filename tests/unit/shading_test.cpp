// Surface shading of the path tracer: textures (nearest and bilinear, wrap modes, sRGB, in/out
// transforms), vertex and primitive colors, shading normals under non-uniform scale, the
// physicallyBased BSDF against an independent evaluation of the glTF model, and its sampling against
// next-event estimation of the same light.
#include "core/render/PathTracer.h"
#include "core/scene/BsdfTables.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <string>

using namespace ripple;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A 2x2 plane filling an orthographic 2x2 view, white matte (or the given material), lit straight from
// above with irradiance pi: each pixel shows base color * texture exactly (a / pi * E * cos 0 = a).
struct LitPlane {
    core::SceneDescription scene;
    core::RenderSettings settings;
    core::Camera camera = test::lookingDown(1.0f, 2.0f);

    LitPlane() {
        scene = test::sceneOf(test::squareMesh(2.0f));
        core::Material white;
        white.baseColor = glm::vec3(1.0f);
        scene.materials.push_back(white);
        core::Light sun;
        sun.direction = {0.0f, 0.0f, -1.0f};
        sun.intensity = float(kPi);
        scene.lights.push_back(sun);
        settings.maxPathLength = 1;
    }
    test::Rendered render() const { return test::render(scene, camera, settings); }
};

core::Texture rgba8(uint32_t width, uint32_t height, std::vector<uint8_t> texels, core::Texture::Format format) {
    core::Texture t;
    t.width = width;
    t.height = height;
    t.format = format;
    t.texels = std::move(texels);
    t.linearFilter = false;
    return t;
}

double srgbDecode(uint8_t byte) {
    const double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

bool near(const glm::vec4& c, const glm::dvec3& expected) {
    for (int k = 0; k < 3; ++k)
        if (std::abs(c[k] - expected[k]) > 1e-5 * expected[k] + 1e-7) return false;
    return true;
}

// Pixels (of a 32x32 image) whose colour differs from `expected(x, y)`.
template <class Expected>
uint64_t mismatches(const test::Rendered& r, Expected&& expected) {
    uint64_t wrong = 0;
    for (uint32_t y = 0; y < r.size.y; ++y)
        for (uint32_t x = 0; x < r.size.x; ++x) wrong += !near(r.at(x, y), expected(x, y));
    return wrong;
}

}  // namespace

// Texel row 0 is at v = 0 (the bottom of the image here); each quadrant of the image shows one texel.
// sRGB bytes are decoded, unorm bytes are divided by 255. Exact within 1e-5 relative.
TEST_CASE("shading: nearest texture lookup, sRGB decoding, one texel per image quadrant") {
    test::ValidationGuard guard;
    const std::vector<uint8_t> texels = {255, 0, 0, 255, 0, 128, 0, 255,   // row 0 (v < 0.5)
                                         0, 0, 64, 255, 10, 20, 30, 255};  // row 1
    for (auto format : {core::Texture::Format::Rgba8Srgb, core::Texture::Format::Rgba8Unorm}) {
        LitPlane plane;
        plane.scene.textures.push_back(rgba8(2, 2, texels, format));
        plane.scene.materials[0].baseColorTexture = 0;
        const test::Rendered r = plane.render();
        auto decode = [&](uint8_t b) { return format == core::Texture::Format::Rgba8Srgb ? srgbDecode(b) : b / 255.0; };
        CHECK(mismatches(r, [&](uint32_t x, uint32_t y) {
                  const uint8_t* t = &texels[4 * ((y / 16) * 2 + x / 16)];
                  return glm::dvec3(decode(t[0]), decode(t[1]), decode(t[2]));
              }) == 0);
    }
}

// inTransform scales texcoords by 2, so texture coordinate u spans [0, 2) across the image: repeat shows
// columns 0,1,0,1 in the four vertical bands, mirrored repeat 0,1,1,0, clamp to edge 0,1,1,1. The out
// transform swaps red and blue.
TEST_CASE("shading: wrap modes and texture transforms") {
    test::ValidationGuard guard;
    const std::vector<uint8_t> texels = {200, 0, 0, 255, 0, 0, 100, 255};  // 2x1: reddish, bluish
    const int bands[3][4] = {{0, 1, 0, 1}, {0, 1, 1, 0}, {0, 1, 1, 1}};
    const core::Texture::Wrap modes[3] = {core::Texture::Wrap::Repeat, core::Texture::Wrap::MirrorRepeat,
                                          core::Texture::Wrap::ClampToEdge};
    for (int m = 0; m < 3; ++m) {
        CAPTURE(m);
        LitPlane plane;
        core::Texture t = rgba8(2, 1, texels, core::Texture::Format::Rgba8Unorm);
        t.wrapS = modes[m];
        t.inTransform = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, 1.0f));
        t.outTransform = glm::mat4(glm::vec4(0, 0, 1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 0, 1));
        plane.scene.textures.push_back(t);
        plane.scene.materials[0].baseColorTexture = 0;
        const test::Rendered r = plane.render();
        CHECK(mismatches(r, [&](uint32_t x, uint32_t) {
                  const uint8_t* texel = &texels[4 * bands[m][x / 8]];
                  return glm::dvec3(texel[2], texel[1], texel[0]) / 255.0;
              }) == 0);
    }
}

// A 2x1 float texture (0 then 1) with bilinear filtering and clamp to edge: along u the value is
// clamp((u - 1/4) / (1/2), 0, 1) (texel centres at u = 1/4 and 3/4). It rises with u, so each pixel lies
// between its value at the footprint's left and right edges (1e-5 slack). The NaN in the blue of the second
// texel is replaced by 0 at scene build, and reported.
TEST_CASE("shading: bilinear filtering of a float texture; NaN texels repaired") {
    test::ValidationGuard guard;
    LitPlane plane;
    const float texel[8] = {0, 0, 0, 1, 1, 1, std::numeric_limits<float>::quiet_NaN(), 1};
    core::Texture t;
    t.width = 2;
    t.height = 1;
    t.format = core::Texture::Format::Rgba32Float;
    t.texels.resize(sizeof(texel));
    std::memcpy(t.texels.data(), texel, sizeof(texel));
    t.wrapS = t.wrapT = core::Texture::Wrap::ClampToEdge;
    plane.scene.textures.push_back(t);
    plane.scene.materials[0].baseColorTexture = 0;
    core::Scene scene(test::testContext(), plane.scene);
    CHECK(scene.report().messages.size() == 1);
    CHECK(scene.report().messages[0] == "texture 0: 1 NaN or Inf texel value(s) replaced by 0");
    const test::Rendered r = plane.render();
    auto ramp = [](double u) { return std::clamp((u - 0.25) / 0.5, 0.0, 1.0); };
    uint64_t outside = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const double v = r.at(x, y).r;
            outside += v < ramp(x / 32.0) - 1e-5 || v > ramp((x + 1) / 32.0) + 1e-5 || r.at(x, y).g != r.at(x, y).r;
            outside += r.at(x, y).b != 0.0f;  // blue is 0 in both texels once the NaN is repaired
        }
    CHECK(outside == 0);
}

// baseColorFromVertexColor: primitive colors paint each triangle (the diagonal from (-1,-1) to (1,1)
// splits them; pixels it crosses are left out); vertex colors interpolate, red rising linearly with x,
// so each pixel lies within its footprint's range.
TEST_CASE("shading: primitive and vertex colors replace the base color") {
    test::ValidationGuard guard;
    LitPlane plane;
    plane.scene.materials[0].baseColorFromVertexColor = true;
    plane.scene.meshes[0].primitiveColors = {{0.2f, 0.4f, 0.6f, 1.0f}, {0.9f, 0.1f, 0.3f, 1.0f}};
    const test::Rendered prim = plane.render();
    uint64_t wrong = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            if (x == y) continue;
            const glm::vec4 expected = plane.scene.meshes[0].primitiveColors[x > y ? 0 : 1];
            wrong += !near(prim.at(x, y), glm::dvec3(expected));
        }
    CHECK(wrong == 0);

    plane.scene.meshes[0].colors = {{0, 0.5f, 0, 1}, {1, 0.5f, 0, 1}, {1, 0.5f, 0, 1}, {0, 0.5f, 0, 1}};
    const test::Rendered vertex = plane.render();
    uint64_t outside = 0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const glm::vec4 c = vertex.at(x, y);
            outside += c.r < x / 32.0f - 1e-5f || c.r > (x + 1) / 32.0f + 1e-5f || std::abs(c.g - 0.5f) > 1e-5f;
        }
    CHECK(outside == 0);
}

// Vertex normals all along (1, 0, 1) under an instance that scales x by 2: normals transform by the
// inverse transpose, to (1/2, 0, 1), so with light from straight above each pixel is cos = 1 / sqrt(1.25).
TEST_CASE("shading: interpolated normals follow the inverse transpose of the instance transform") {
    test::ValidationGuard guard;
    LitPlane plane;
    plane.scene.meshes[0].normals.assign(4, glm::normalize(glm::vec3(1, 0, 1)));
    plane.scene.instances[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, 1.0f));
    const test::Rendered r = plane.render();
    CHECK(mismatches(r, [](uint32_t, uint32_t) { return glm::dvec3(1.0 / std::sqrt(1.25)); }) == 0);
}

namespace {

// The glTF 2.0 metallic-roughness BRDF (spec appendix B) times cos(n, l), written independently of the
// shader in double: GGX D with alpha = roughness^2, height-correlated Smith G, Schlick Fresnel mixed from
// the ior's F0 to the base color by metallic, Lambert diffuse weighted by (1 - metallic)(1 - F).
glm::dvec3 gltfBrdfCos(glm::dvec3 base, double metallic, double roughness, double ior, glm::dvec3 n, glm::dvec3 v,
                       glm::dvec3 l) {
    const double a2 = std::pow(roughness, 4.0);
    const glm::dvec3 h = glm::normalize(v + l);
    const double nl = glm::dot(n, l), nv = glm::dot(n, v), nh = glm::dot(n, h), vh = glm::dot(v, h);
    const double d = nh * nh * (a2 - 1.0) + 1.0;
    const double D = a2 / (kPi * d * d);
    auto lambda = [&](double c) { return 0.5 * (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))); };
    const double G = 1.0 / (1.0 + lambda(nv) + lambda(nl));
    const double f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
    const double w = std::pow(1.0 - vh, 5.0);
    const glm::dvec3 F0 = glm::mix(glm::dvec3(f0), base, metallic);
    const glm::dvec3 F = F0 + (1.0 - F0) * w;
    const double Fd = f0 + (1.0 - f0) * w;
    // Energy compensation (shaders/bsdf.glsl): the specular lobe scaled by 1 + F0 (1 - E) / E, the diffuse
    // lobe weighted by what the dielectric specular leaves at v, from the GGX albedo tables.
    const double E = core::bsdfEnergyLookup(0, float(nv), float(roughness * roughness));
    const double W = core::bsdfEnergyLookup(1, float(nv), float(roughness * roughness));
    const double dielectricAlbedo = (f0 * (E - W) + W) * (1.0 + f0 * (1.0 - E) / E);
    (void)Fd;
    const glm::dvec3 specular = F * D * G / (4.0 * nv * nl) * (1.0 + F0 * ((1.0 - E) / E));
    const glm::dvec3 diffuse = (1.0 - metallic) * (1.0 - dielectricAlbedo) * base / kPi;
    return (specular + diffuse) * nl;
}

}  // namespace

// physicallyBased under a directional light, direct lighting only, seen straight from above: each pixel
// is BRDF * cos * E, evaluated here independently. 2e-4 relative: float pow and the GPU's sqrt.
TEST_CASE("shading: physicallyBased BSDF equals the glTF metallic-roughness model") {
    test::ValidationGuard guard;
    for (auto [metallic, roughness] : {std::pair{0.3f, 0.5f}, std::pair{1.0f, 0.2f}, std::pair{0.0f, 1.0f}}) {
        CAPTURE(metallic);
        LitPlane plane;
        core::Material& m = plane.scene.materials[0];
        m.kind = core::Material::Kind::PhysicallyBased;
        m.baseColor = {0.9f, 0.6f, 0.3f};
        m.metallic = metallic;
        m.roughness = roughness;
        const double theta = 0.7, irradiance = 2.0;
        plane.scene.lights[0].direction = -glm::vec3(std::sin(theta), 0.0, std::cos(theta));
        plane.scene.lights[0].intensity = float(irradiance);
        const test::Rendered r = plane.render();
        const glm::dvec3 expected = irradiance * gltfBrdfCos(glm::dvec3(m.baseColor), metallic, roughness, 1.5, {0, 0, 1},
                                                             {0, 0, 1}, {std::sin(theta), 0.0, std::cos(theta)});
        uint64_t wrong = 0;
        for (const glm::vec4& c : r.color)
            for (int k = 0; k < 3; ++k) wrong += std::abs(c[k] - expected[k]) > 2e-4 * expected[k];
        CHECK(wrong == 0);
    }
}

namespace {

struct MeanAndError {
    double mean = 0.0, standardError = 0.0;
};

// Image mean of the red channel, and its standard error from the spread of the pixels (each an
// independent estimate of the same value, as the camera sees a tiny patch).
MeanAndError redStatistics(const test::Rendered& r) {
    double sum = 0.0, sum2 = 0.0;
    for (const glm::vec4& c : r.color) {
        sum += c.r;
        sum2 += double(c.r) * c.r;
    }
    const double n = double(r.color.size()), mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0))};
}

// A floor of `floor` under a ceiling of radiance 1.5 (corner + [0, 1] alongX + [0, 1] alongY): once an
// emissive rectangle, which only the trace finds, once a quad light facing the floor, which light sampling
// and the rays that test it find. Viewed by ceilingCamera(), 60 degrees off the normal, the mirror
// direction points into the ceiling.
struct CeilingScenes {
    core::SceneDescription emitter, lit;
};

CeilingScenes ceilingOver(const core::Material& floor) {
    const glm::vec3 corner(-1.0f, -3.0f, 1.0f), alongX(5.5f, 0.0f, 0.0f), alongY(0.0f, 6.0f, 0.0f);
    CeilingScenes out{test::sceneOf(test::squareMesh(100.0f)), test::sceneOf(test::squareMesh(100.0f))};
    out.emitter.materials = {floor};
    core::TriangleMesh ceiling;
    ceiling.positions = {corner, corner + alongX, corner + alongX + alongY, corner + alongY};
    ceiling.indices = {{0, 1, 2}, {0, 2, 3}};
    out.emitter.meshes.push_back(ceiling);
    core::Material glow;
    glow.baseColor = glm::vec3(0.0f);
    glow.emissive = glm::vec3(1.5f);
    out.emitter.materials.push_back(glow);
    out.emitter.instances.push_back({{core::GeometryKind::Triangles, 1}, glm::mat4(1.0f), 1});

    out.lit.materials = {floor};
    core::Light quad;
    quad.kind = core::Light::Kind::Quad;
    quad.position = corner;
    quad.edge1 = alongY;  // cross(edge1, edge2) points down, at the floor
    quad.edge2 = alongX;
    quad.intensity = 1.5f;
    out.lit.lights.push_back(quad);
    return out;
}

core::Camera ceilingCamera() {
    core::Camera camera = test::lookingDown(0.0f, 1e-3f);
    camera.direction = {0.866f, 0.0f, -0.5f};
    camera.position = -0.4f * camera.direction;
    return camera;
}

}  // namespace

// The same light reached two ways: an emissive rectangle above a physicallyBased floor, found only by
// BSDF sampling (one bounce), and a quad light in the same place, found only by next-event estimation.
// The two estimates agree when sampleBsdf's directions and weights match evalBsdf; they must agree within
// 5 standard errors (measured from the images). The view is 60 degrees off the normal, where the visible
// normal pdf differs from the plain D one by 20% at roughness 0.8, and the mirror direction points into
// the light.
TEST_CASE("shading: BSDF sampling and light sampling of the same emitter agree") {
    test::ValidationGuard guard;
    const core::Camera camera = ceilingCamera();
    core::RenderSettings settings;
    settings.pixelSamples = 32;
    for (auto [metallic, roughness] : {std::pair{1.0f, 0.8f}, std::pair{0.3f, 0.4f}}) {
        CAPTURE(roughness);
        core::Material floor;
        floor.kind = core::Material::Kind::PhysicallyBased;
        floor.baseColor = {0.8f, 0.8f, 0.8f};
        floor.metallic = metallic;
        floor.roughness = roughness;
        const CeilingScenes scenes = ceilingOver(floor);
        settings.maxPathLength = 2;
        const MeanAndError bsdf = redStatistics(test::render(scenes.emitter, camera, settings));
        settings.maxPathLength = 1;
        const MeanAndError light = redStatistics(test::render(scenes.lit, camera, settings));

        MESSAGE("roughness " << roughness << ": BSDF sampling " << bsdf.mean << " +- " << bsdf.standardError
                             << ", light sampling " << light.mean << " +- " << light.standardError);
        CHECK(bsdf.mean > 0.1);
        CHECK(std::abs(bsdf.mean - light.mean) <= 5.0 * std::hypot(bsdf.standardError, light.standardError));
    }
}

// A white metal mirror (roughness 0, a delta lobe: shaders/bsdf.glsl) reflecting a ceiling of radiance 1.5,
// once an emissive rectangle (found by the trace) and once a quad light (tested by the reflected ray): the
// mirror shows 1.5 (F = 1, within 1% for the albedo tables), the same in every sample (standard error
// below 1e-4), and light sampling adds nothing, so the quad light is not counted twice.
TEST_CASE("shading: a mirror reflects an emitter exactly, without noise") {
    test::ValidationGuard guard;
    core::Material mirror;
    mirror.kind = core::Material::Kind::PhysicallyBased;
    mirror.baseColor = glm::vec3(1.0f);
    mirror.metallic = 1.0f;
    mirror.roughness = 0.0f;
    core::RenderSettings settings;
    settings.pixelSamples = 8;
    settings.maxPathLength = 2;
    const CeilingScenes scenes = ceilingOver(mirror);
    for (const core::SceneDescription* scene : {&scenes.emitter, &scenes.lit}) {
        const bool light = scene == &scenes.lit;
        CAPTURE(light);
        const MeanAndError m = redStatistics(test::render(*scene, ceilingCamera(), settings));
        MESSAGE(std::string(light ? "quad light: " : "emissive rectangle: ") << m.mean << " +- " << m.standardError);
        CHECK(std::abs(m.mean - 1.5) <= 0.015);
        CHECK(m.standardError < 1e-4);
    }
}

// A white metal sphere under ambient light (4 samples per pixel): energy-compensated GGX reflects what it
// receives, so the sphere's mean is the ambient radiance within 3%.
TEST_CASE("shading: a white rough metal sphere reflects what it receives") {
    test::ValidationGuard guard;
    core::SphereSet sphere;
    sphere.centers = {{0.0f, 0.0f, 0.0f}};
    sphere.radii = {1.0f};
    core::SceneDescription d = test::sceneOf(sphere);
    core::Material metal;
    metal.kind = core::Material::Kind::PhysicallyBased;
    metal.baseColor = glm::vec3(1.0f);
    metal.metallic = 1.0f;
    metal.roughness = 0.5f;
    d.materials.push_back(metal);
    core::RenderSettings settings;
    settings.ambientRadiance = 1.0f;
    settings.maxPathLength = 4;
    settings.pixelSamples = 4;
    const test::Rendered r = test::render(d, test::lookingDown(3.0f, 1.4f), settings);
    double sum = 0.0;
    uint64_t hits = 0;
    for (const glm::vec4& c : r.color) {
        if (c.a < 1.0f) continue;
        ++hits;
        sum += c.r;
    }
    REQUIRE(hits > 500);
    // With energy compensation a single sample may exceed 1 (the lobe is scaled by 1 / E), but the pixels'
    // mean stays the ambient radiance (light_transport_test.cpp holds the 1% furnace per roughness).
    MESSAGE("white rough metal sphere: mean " << sum / double(hits) << " of the ambient radiance");
    CHECK(sum / double(hits) > 0.97);
    CHECK(sum / double(hits) < 1.03);
}
