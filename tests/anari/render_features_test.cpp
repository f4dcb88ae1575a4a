// Render tests of the ANARI features beyond the basic subtypes: samplers (image1D, image2D driving every
// physicallyBased parameter), hdri/spot/ring lights, cameras, cone/curve/capped cylinder geometry, the id,
// albedo and normal channels, and the renderer's maxRadiance and seed. Exact values where the scene allows them
// (emission seen directly, ids), references (tests/anari/references, RIPPLE_UPDATE_REFERENCES=1) elsewhere.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>
#include <nanovdb/util/Primitives.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

constexpr glm::uvec2 kSize{48, 48};
constexpr int32_t kSamples = 64;
// Reference metric: RMSE over linear RGB of all pixels between 8-bit sRGB images (48x48, paths of 3;
// 64 samples per pixel, 128 for the sampler scene, 256 for spot and ring). The same build repeats a
// reference exactly. The threshold allows for a change of sampling: two independent renders differ by
// RMSE 0.010 (omnidirectional) to 0.020 (spot and ring), measured with lavapipe; a missing sampler, a
// flipped texture or a light aimed elsewhere moves these scenes by far more.
constexpr double kReferenceRmse = 0.03;
constexpr uint32_t kNoId = std::numeric_limits<uint32_t>::max();

void checkReference(RenderSession& s, const char* name, const Image& image) {
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    CHECK(ripple::test::compareWithReference(name, image, kReferenceRmse) <= kReferenceRmse);
}

// An upright quad in the z = 0 plane from (x0, y0) to (x1, y1), attribute0 = (u, v) over it.
ANARIGeometry uvQuad(RenderSession& s, glm::vec2 lower, glm::vec2 upper) {
    ANARIGeometry quad = s.keep(anariNewGeometry(s.device, "quad"));
    s.setObject(quad, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{lower.x, lower.y, 0}, {upper.x, lower.y, 0},
                                                                    {upper.x, upper.y, 0}, {lower.x, upper.y, 0}}));
    s.setObject(quad, "vertex.attribute0", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC2, std::vector<glm::vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    s.commit(quad);
    return quad;
}

template <class T>
ANARIArray2D image2D(RenderSession& s, ANARIDataType type, uint32_t width, uint32_t height, const std::vector<T>& texels) {
    ANARIArray2D image = s.keep(anariNewArray2D(s.device, nullptr, nullptr, nullptr, type, width, height));
    std::memcpy(anariMapArray(s.device, image), texels.data(), texels.size() * sizeof(T));
    anariUnmapArray(s.device, image);
    return image;
}

// A managed 3D array holding `size` bytes copied from `bytes`.
ANARIArray3D array3D(RenderSession& s, ANARIDataType type, glm::uvec3 dims, const void* bytes, size_t size) {
    ANARIArray3D array = s.keep(anariNewArray3D(s.device, nullptr, nullptr, nullptr, type, dims.x, dims.y, dims.z));
    if (size > 0) std::memcpy(anariMapArray(s.device, array), bytes, size);
    else anariMapArray(s.device, array);
    anariUnmapArray(s.device, array);
    return array;
}

// A committed structuredRegular field of FLOAT32 samples (x fastest); origin and spacing as the spec's defaults.
ANARISpatialField floatField(RenderSession& s, glm::uvec3 dims, const std::vector<float>& values,
                             glm::vec3 origin = glm::vec3(0.0f), glm::vec3 spacing = glm::vec3(1.0f)) {
    ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "structuredRegular"));
    s.setObject(field, "data", ANARI_ARRAY3D, array3D(s, ANARI_FLOAT32, dims, values.data(), values.size() * sizeof(float)));
    s.set(field, "origin", origin);
    s.set(field, "spacing", spacing);
    s.commit(field);
    return field;
}

// f(x, y, z) = x y z sampled on a 5^3 grid over the unit cube (trilinear in every cell, so the interpolant is
// f itself), as a committed field.
ANARISpatialField xyzField(RenderSession& s) {
    const uint32_t n = 5;
    std::vector<float> voxels;
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) voxels.push_back(float(i) / (n - 1) * float(j) / (n - 1) * float(k) / (n - 1));
    return floatField(s, glm::uvec3(n), voxels, glm::vec3(0.0f), glm::vec3(1.0f / (n - 1)));
}

// A committed 2x2x2 UFIXED8 field of value 255 (1.0 after normalisation) spanning [-1, 1]^2 x [0, 1].
ANARISpatialField unitSlabField(RenderSession& s) {
    ANARIArray3D voxels = s.keep(anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_UFIXED8, 2, 2, 2));
    std::memset(anariMapArray(s.device, voxels), 255, 8);
    anariUnmapArray(s.device, voxels);
    ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "structuredRegular"));
    s.setObject(field, "data", ANARI_ARRAY3D, voxels);
    s.set(field, "origin", glm::vec3(-1.0f, -1.0f, 0.0f));
    s.set(field, "spacing", glm::vec3(2.0f, 2.0f, 1.0f));
    s.commit(field);
    return field;
}

// A committed sampler of `image` (image1D or image2D) with the given filter and outTransform.
ANARISampler imageSampler(RenderSession& s, const char* subtype, ANARIObject image, const char* filter,
                          const glm::mat4& outTransform = glm::mat4(1.0f)) {
    ANARISampler sampler = s.keep(anariNewSampler(s.device, subtype));
    s.setObject(sampler, "image", std::string(subtype) == "image1D" ? ANARI_ARRAY1D : ANARI_ARRAY2D, image);
    s.set(sampler, "filter", filter);
    s.setRaw(sampler, "outTransform", ANARI_FLOAT32_MAT4, &outTransform);
    s.commit(sampler);
    return sampler;
}

// Emission seen directly: no lights, black background and base colour, one bounce, so each pixel that
// sees the surface is exactly its emission (float channel).
ANARIRenderer emissionOnlyRenderer(RenderSession& s) {
    return s.renderer(1, 1, glm::vec4(0, 0, 0, 1));
}

// Orthographic, looking down -z at the origin; the frame's aspect sets the width of the view.
// A world with one instance, id `instanceId`, of a group holding `object` as its only `parameter`
// ("surface" or "volume", of ANARI type `type`).
ANARIWorld instancedWorld(RenderSession& s, const char* parameter, ANARIDataType type, ANARIObject object,
                          uint32_t instanceId) {
    ANARIGroup group = s.keep(anariNewGroup(s.device));
    s.setObject(group, parameter, ANARI_ARRAY1D, s.objects(type, {object}));
    s.commit(group);
    ANARIInstance instance = s.keep(anariNewInstance(s.device, "transform"));
    s.setObject(instance, "group", ANARI_GROUP, group);
    s.setRaw(instance, "id", ANARI_UINT32, &instanceId);
    s.commit(instance);
    ANARIWorld world = s.keep(anariNewWorld(s.device));
    s.setObject(world, "instance", ANARI_ARRAY1D, s.objects(ANARI_INSTANCE, {instance}));
    s.commit(world);
    return world;
}

ANARICamera frontCamera(RenderSession& s, float height = 2.0f) {
    return s.orthographic(glm::vec3(0, 0, 3), glm::vec3(0, 0, -1), height);  // up: the default (0, 1, 0)
}

ANARIMaterial physicallyBased(RenderSession& s) {
    ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
    return material;
}

// A stage like render_test's: grey floor, a directional light unless given lights, perspective camera.
Image renderStage(RenderSession& s, std::vector<ANARISurface> surfaces, std::vector<ANARILight> lights = {},
                  ANARICamera camera = nullptr, ANARIRenderer renderer = nullptr) {
    surfaces.push_back(s.surface(s.floor(), s.matte(glm::vec3(0.7f))));
    if (lights.empty()) lights.push_back(s.directional(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.4f)), 3.0f));
    if (!camera) camera = s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f});
    if (!renderer) renderer = s.renderer(kSamples, 3);
    return s.render(s.frame(s.world(surfaces, lights), camera, renderer, kSize, ANARI_UFIXED8_RGBA_SRGB));
}

template <class T>
std::vector<T> mapChannel(RenderSession& s, ANARIFrame frame, const char* name, ANARIDataType expected) {
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const void* data = anariMapFrame(s.device, frame, name, &width, &height, &type);
    REQUIRE_MESSAGE(data, s.log.dump());
    CHECK(type == expected);
    const auto* values = static_cast<const T*>(data);
    std::vector<T> out(values, values + size_t(width) * height);
    anariUnmapFrame(s.device, frame, name);
    return out;
}

void setChannel(RenderSession& s, ANARIFrame frame, const char* name, ANARIDataType type) {
    s.setRaw(frame, name, ANARI_DATA_TYPE, &type);
}

}  // namespace

TEST_CASE("emissive from an image2D sampler (nearest) is seen exactly, texel by texel, the right way up") {
    RenderSession s;
    // 2x2 texels; row 0 is v = 0, at the bottom of the quad (frames also start at the bottom).
    const std::vector<glm::vec4> texels{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    ANARISampler emissive = imageSampler(s, "image2D", image2D(s, ANARI_FLOAT32_VEC4, 2, 2, texels), "nearest",
                                         glm::mat4(2.0f));  // scales rgb (and alpha) by 2
    ANARIMaterial material = physicallyBased(s);
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.setObject(material, "emissive", ANARI_SAMPLER, emissive);
    s.commit(material);
    ANARISurface surface = s.surface(uvQuad(s, {-1, -1}, {1, 1}), material);
    ANARIFrame frame = s.frame(s.world({surface}, {}), frontCamera(s), emissionOnlyRenderer(s), {8, 8},
                               ANARI_FLOAT32_VEC4);
    const Image image = s.render(frame);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    // Pixel centres of an 8x8 orthographic view of the quad: each 4x4 block sees one texel.
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const glm::vec3 expected = 2.0f * glm::vec3(texels[(y / 4) * 2 + x / 4]);
            const glm::vec3 got(image.at(x, y));
            INFO("pixel " << x << "," << y);
            CHECK(glm::all(glm::lessThan(glm::abs(got - expected), glm::vec3(1e-4f))));
        }
}

TEST_CASE("image1D sampler: a colour map along u, linear filter between texel centres, wrapMode") {
    // Two texels: black at u = 0.25, white at u = 0.75; clamped beyond, linear between. Then shifted by
    // inOffset 0.5 with "wrapMode" (the spec's name for image1D) "repeat": u + 0.5 past 1 wraps to u - 0.5;
    // the same with "wrapMode1", the name the SDK's own test scenes give it.
    for (const std::string wrapName : {"", "wrapMode", "wrapMode1"}) {
    CAPTURE(wrapName);
    const bool shiftedAndRepeated = !wrapName.empty();
    RenderSession s;
    ANARIArray1D map = s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>{{0, 0, 0, 1}, {1, 1, 1, 1}});
    ANARISampler sampler = imageSampler(s, "image1D", map, "linear");
    if (shiftedAndRepeated) {
        s.set(sampler, wrapName.c_str(), "repeat");
        s.set(sampler, "inOffset", glm::vec4(0.5f, 0.0f, 0.0f, 0.0f));
        s.commit(sampler);
    }
    ANARIMaterial material = physicallyBased(s);
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.setObject(material, "emissive", ANARI_SAMPLER, sampler);
    s.commit(material);
    // A 64x2 frame 1/16 high sees 2 units across: pixel x covers u in [x, x + 1] / 64. Camera rays are
    // jittered within their pixel and the map's slope is 2, so a pixel may differ from the value at its
    // centre by up to 1/64 (one sample each): the threshold.
    ANARIFrame frame = s.frame(s.world({s.surface(uvQuad(s, {-1, -1}, {1, 1}), material)}, {}),
                               frontCamera(s, 1.0f / 16.0f), emissionOnlyRenderer(s), {64, 2}, ANARI_FLOAT32_VEC4);
    const Image image = s.render(frame);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    for (uint32_t x = 0; x < 64; ++x) {
        const float u = (float(x) + 0.5f) / 64.0f;
        // Repeating, the texel centres recur every 1: the map rises over [0.25, 0.75] and falls back linearly
        // from white at 0.75 to black at 1.25 (= 0.25); shifted by 0.5, pixel u reads u + 0.5.
        float expected = std::clamp((u - 0.25f) / 0.5f, 0.0f, 1.0f);
        if (shiftedAndRepeated) {
            const float v = u + 0.5f > 1.0f ? u - 0.5f : u + 0.5f;
            expected = v < 0.25f ? 0.5f - 2.0f * v : v <= 0.75f ? (v - 0.25f) / 0.5f : 1.0f - 2.0f * (v - 0.75f);
        }
        INFO("pixel " << x << " u " << u);
        CHECK(std::abs(image.at(x, 0).r - expected) <= 1.0f / 64.0f + 1e-4f);
        CHECK(std::abs(image.at(x, 1).g - expected) <= 1.0f / 64.0f + 1e-4f);
    }
    }
}

TEST_CASE("physicallyBased from samplers: glTF metallic-roughness channels, normal map, opacity mask") {
    RenderSession s;
    // metallicRoughness texture: G = roughness, B = metallic; left half rough dielectric, right half
    // polished metal. Picked by outTransform rows, as the glTF importer does.
    const std::vector<uint8_t> mr{0, 230, 0, 255, 0, 20, 255, 255};
    ANARIArray2D mrImage = image2D(s, ANARI_UFIXED8_VEC4, 2, 1, mr);
    glm::mat4 pickG(0.0f), pickB(0.0f);
    pickG[1][0] = 1.0f;
    pickB[2][0] = 1.0f;
    // A normal map tilting normals alternately left and right in 4 stripes.
    const std::vector<uint8_t> normals{56, 128, 220, 255, 200, 128, 220, 255, 56, 128, 220, 255, 200, 128, 220, 255};
    // Opacity: a hole in the middle texel (mask mode, cutoff 0.5).
    const std::vector<float> opacity{1, 0, 1};
    ANARIMaterial material = physicallyBased(s);
    s.set(material, "baseColor", glm::vec3(0.9f, 0.6f, 0.3f));
    s.setObject(material, "metallic", ANARI_SAMPLER, imageSampler(s, "image2D", mrImage, "nearest", pickB));
    s.setObject(material, "roughness", ANARI_SAMPLER, imageSampler(s, "image2D", mrImage, "nearest", pickG));
    s.setObject(material, "normal", ANARI_SAMPLER,
                imageSampler(s, "image2D", image2D(s, ANARI_UFIXED8_VEC4, 4, 1, normals), "nearest"));
    s.setObject(material, "opacity", ANARI_SAMPLER,
                imageSampler(s, "image1D", s.array(ANARI_FLOAT32, opacity), "nearest"));
    s.set(material, "alphaMode", "mask");
    s.commit(material);
    ANARIRenderer renderer = s.renderer(2 * kSamples, 3);
    s.set(renderer, "ambientRadiance", 0.6f);
    s.commit(renderer);
    checkReference(s, "sampler_physically_based",
                   renderStage(s, {s.surface(uvQuad(s, {-1.2f, 0.05f}, {1.2f, 1.5f}), material)}, {}, nullptr, renderer));
}

// The normal channel shows the normal-mapped shading normal, so the tangent frame is checked exactly: from
// attribute0 (u along +x), or from vertex.tangent, whose w is the handedness of the bitangent.
TEST_CASE("normal map frame: vertex.tangent (VEC3, or VEC4 with handedness) replaces the frame from attribute0") {
    const float h = std::sqrt(0.5f);
    struct Case {
        std::vector<glm::vec4> tangent;  // empty: unset; w = 0 marks a VEC3 array
        glm::vec3 mapNormal;             // the normal map's one texel, tangent space
        glm::vec3 expected;              // world space
    };
    const Case cases[] = {
        {{}, {h, 0, h}, {h, 0, h}},                              // t = +x from the texcoords
        {std::vector<glm::vec4>(4, {0, 1, 0, 0}), {h, 0, h}, {0, h, h}},    // t = +y
        {std::vector<glm::vec4>(4, {0, 1, 0, 1}), {0, h, h}, {-h, 0, h}},   // b = cross(n, t) = -x
        {std::vector<glm::vec4>(4, {0, 1, 0, -1}), {0, h, h}, {h, 0, h}},   // mirrored: b = +x
    };
    for (const Case& c : cases) {
        CAPTURE(c.expected);
        RenderSession s;
        ANARIGeometry quad = uvQuad(s, {-1.5f, -1.5f}, {1.5f, 1.5f});
        if (!c.tangent.empty()) {
            if (c.tangent[0].w == 0.0f) {
                std::vector<glm::vec3> xyz;
                for (const glm::vec4& t : c.tangent) xyz.emplace_back(t);
                s.setObject(quad, "vertex.tangent", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, xyz));
            } else {
                s.setObject(quad, "vertex.tangent", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, c.tangent));
            }
            s.commit(quad);
        }
        const std::vector<glm::vec4> texel{glm::vec4(0.5f * c.mapNormal + 0.5f, 1.0f)};
        ANARIMaterial material = physicallyBased(s);
        s.setObject(material, "normal", ANARI_SAMPLER, imageSampler(s, "image2D", image2D(s, ANARI_FLOAT32_VEC4, 1, 1, texel), "nearest"));
        s.commit(material);
        ANARIFrame frame = s.frame(s.world({s.surface(quad, material)}, {}), frontCamera(s), s.renderer(1, 1), {4, 4},
                                   ANARI_FLOAT32_VEC4);
        setChannel(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
        s.commit(frame);
        s.render(frame);
        const auto normal = mapChannel<glm::vec3>(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        for (const glm::vec3& n : normal) {
            INFO("normal " << n.x << " " << n.y << " " << n.z);
            CHECK(glm::all(glm::lessThan(glm::abs(n - c.expected), glm::vec3(1e-5f))));
        }
    }
}

TEST_CASE("hdri light: a uniform environment lights a convex matte sphere to albedo times radiance") {
    RenderSession s;
    const std::vector<glm::vec3> radiance(8 * 4, glm::vec3(0.5f));
    ANARILight hdri = s.keep(anariNewLight(s.device, "hdri"));
    s.setObject(hdri, "radiance", ANARI_ARRAY2D, image2D(s, ANARI_FLOAT32_VEC3, 8, 4, radiance));
    s.set(hdri, "scale", 2.0f);
    s.commit(hdri);
    ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(sphere, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0, 0, 0}}));
    s.set(sphere, "radius", 0.9f);
    s.commit(sphere);
    // One bounce: a convex surface sees only the environment, so the expected pixel is albedo * L = 0.8.
    ANARIRenderer renderer = s.renderer(256, 1, glm::vec4(0, 0, 0, 1));
    ANARIFrame frame = s.frame(s.world({s.surface(sphere, s.matte(glm::vec3(0.8f)))}, {hdri}), frontCamera(s),
                               renderer, {16, 16}, ANARI_FLOAT32_VEC4);
    const Image image = s.render(frame);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    // Metric: mean over the 4x4 pixels at the centre (all on the sphere) within 2% of 0.8; the standard
    // error of that mean at 256 samples is under 0.5%.
    double sum = 0.0;
    for (uint32_t y = 6; y < 10; ++y)
        for (uint32_t x = 6; x < 10; ++x) sum += image.at(x, y).g;
    CHECK(sum / 16.0 == doctest::Approx(0.8).epsilon(0.02));
}

TEST_CASE("hdri light: sky above, dark ground, seen from a sphere and a floor") {
    RenderSession s;
    // Equirectangular, top row towards +y: a bright blue-white sky band and a dim brown ground.
    std::vector<glm::vec4> texels;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            texels.push_back(y >= 4 ? glm::vec4(0.6f + 0.1f * float(y - 4), 0.8f, 1.5f, 1) : glm::vec4(0.15f, 0.1f, 0.05f, 1));
    // One hot sun texel.
    texels[7 * 16 + 3] = glm::vec4(40, 38, 30, 1);
    ANARILight hdri = s.keep(anariNewLight(s.device, "hdri"));
    s.setObject(hdri, "radiance", ANARI_ARRAY2D, image2D(s, ANARI_FLOAT32_VEC4, 16, 8, texels));
    s.set(hdri, "up", glm::vec3(0, 1, 0));
    s.set(hdri, "direction", glm::vec3(0, 0, -1));
    s.commit(hdri);
    ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(sphere, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0, 0.6f, 0}}));
    s.set(sphere, "radius", 0.6f);
    s.commit(sphere);
    ANARIRenderer renderer = s.renderer(kSamples, 3);
    s.set(renderer, "maxRadiance", 20.0f);
    s.commit(renderer);
    checkReference(s, "light_hdri", renderStage(s, {s.surface(sphere, s.matte({0.8f, 0.8f, 0.8f}))}, {hdri}, nullptr, renderer));
}

TEST_CASE("renderer maxRadiance clamps each contribution; 0 (the default) leaves it alone") {
    RenderSession s;
    ANARIMaterial material = physicallyBased(s);
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.set(material, "emissive", glm::vec3(5.0f, 2.0f, 0.5f));
    s.commit(material);
    ANARIRenderer renderer = emissionOnlyRenderer(s);
    ANARIFrame frame = s.frame(s.world({s.surface(uvQuad(s, {-1, -1}, {1, 1}), material)}, {}), frontCamera(s),
                               renderer, {4, 4}, ANARI_FLOAT32_VEC4);
    Image image = s.render(frame);
    CHECK(image.at(2, 2).r == doctest::Approx(5.0f));
    // Clamped by scaling the contribution so its largest component is the limit: (1, 0.4, 0.1).
    s.set(renderer, "maxRadiance", 1.0f);
    s.commit(renderer);
    image = s.render(frame);
    CHECK(image.at(2, 2).r == doctest::Approx(1.0f));
    CHECK(image.at(2, 2).g == doctest::Approx(0.4f));
    CHECK(image.at(2, 2).b == doctest::Approx(0.1f));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

TEST_CASE("renderer seed: the same seed repeats an image exactly, another draws other samples of it") {
    // A sphere on a floor under an ambient sky, 1 sample of paths of 3: every pixel is noisy.
    RenderSession s;
    ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(sphere, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0, 0.6f, 0}}));
    s.set(sphere, "radius", 0.6f);
    s.commit(sphere);
    ANARIWorld world = s.world({s.surface(s.floor(), s.matte(glm::vec3(0.7f))), s.surface(sphere, s.matte({0.8f, 0.5f, 0.3f}))}, {});
    ANARICamera camera = s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f});
    const auto render = [&](std::optional<int64_t> seed, ANARIDataType type) {
        ANARIRenderer renderer = s.renderer(1, 3);
        s.set(renderer, "ambientRadiance", 1.0f);
        if (seed && type == ANARI_UINT32) {
            const uint32_t value = uint32_t(*seed);
            s.setRaw(renderer, "seed", ANARI_UINT32, &value);
        } else if (seed) {
            s.setInt(renderer, "seed", int32_t(*seed));
        }
        s.commit(renderer);
        return s.render(s.frame(world, camera, renderer, {32, 32}, ANARI_FLOAT32_VEC4));
    };
    const Image unset = render(std::nullopt, ANARI_UINT32), zero = render(0, ANARI_UINT32);
    const Image seven = render(7, ANARI_UINT32), sevenInt = render(7, ANARI_INT32);
    const Image minusOne = render(-1, ANARI_INT32), maxUint = render(0xffffffffu, ANARI_UINT32);
    CHECK(unset.linear == zero.linear);        // 0 is the default
    CHECK(seven.linear == sevenInt.linear);    // INT32 and UINT32 name the same seed
    CHECK(minusOne.linear == maxUint.linear);  // INT32 keeps the bit pattern
    // Other samples: the noisy pixels (those near the sphere; the open floor under a uniform sky is exact)
    // differ, while the image's mean agrees within the noise. An ignored seed would make them all equal.
    size_t differing = 0;
    double meanZero = 0.0, meanSeven = 0.0;
    for (size_t i = 0; i < zero.linear.size(); ++i) {
        differing += zero.linear[i] != seven.linear[i] ? 1 : 0;
        meanZero += zero.linear[i].g;
        meanSeven += seven.linear[i].g;
    }
    CHECK(differing > 50);
    CHECK(meanSeven == doctest::Approx(meanZero).epsilon(0.1));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

TEST_CASE("light spot and ring: cones of light on the floor") {
    RenderSession s;
    ANARILight spot = s.keep(anariNewLight(s.device, "spot"));
    s.set(spot, "position", glm::vec3(-0.8f, 2.0f, 0.0f));
    s.set(spot, "direction", glm::vec3(0.0f, -1.0f, 0.0f));
    s.set(spot, "openingAngle", 0.6f);
    s.set(spot, "falloffAngle", 0.1f);
    s.set(spot, "intensity", 12.0f);
    s.set(spot, "color", glm::vec3(1.0f, 0.8f, 0.5f));
    s.commit(spot);
    ANARILight ring = s.keep(anariNewLight(s.device, "ring"));
    s.set(ring, "position", glm::vec3(0.9f, 1.5f, 0.0f));
    s.set(ring, "direction", glm::vec3(0.0f, -1.0f, 0.0f));
    s.set(ring, "openingAngle", 1.2f);
    s.set(ring, "radius", 0.3f);
    s.set(ring, "innerRadius", 0.15f);
    s.set(ring, "intensity", 6.0f);
    s.set(ring, "color", glm::vec3(0.5f, 0.7f, 1.0f));
    s.commit(ring);
    checkReference(s, "light_spot_ring", renderStage(s, {}, {spot, ring}, nullptr, s.renderer(4 * kSamples, 3)));
}

TEST_CASE("geometry cone, curve and capped cylinders") {
    RenderSession s;
    ANARIGeometry cone = s.keep(anariNewGeometry(s.device, "cone"));
    s.setObject(cone, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1.1f, 0.0f, 0.0f}, {-1.1f, 1.2f, 0.0f}}));
    s.setObject(cone, "vertex.radius", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{0.45f, 0.0f}));
    s.set(cone, "caps", "first");
    s.commit(cone);
    ANARIGeometry curve = s.keep(anariNewGeometry(s.device, "curve"));
    s.setObject(curve, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-0.3f, 0.2f, 0.3f}, {0.0f, 1.0f, 0.0f},
                                                                    {0.4f, 0.5f, -0.2f}, {0.5f, 1.4f, 0.0f}}));
    s.setObject(curve, "vertex.radius", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32, std::vector<float>{0.08f, 0.15f, 0.1f, 0.05f}));
    s.commit(curve);
    ANARIGeometry cylinder = s.keep(anariNewGeometry(s.device, "cylinder"));
    s.setObject(cylinder, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{1.0f, 0.3f, 0.4f}, {1.2f, 1.2f, -0.3f}}));
    s.set(cylinder, "radius", 0.25f);
    s.set(cylinder, "caps", "both");
    s.commit(cylinder);
    checkReference(s, "geometry_cone_curve_caps",
                   renderStage(s, {s.surface(cone, s.matte({0.9f, 0.5f, 0.2f})), s.surface(curve, s.matte({0.3f, 0.8f, 0.4f})),
                                   s.surface(cylinder, s.matte({0.4f, 0.5f, 0.9f}))}));
}

TEST_CASE("cameras: perspective with depth of field, and omnidirectional") {
    RenderSession s;
    ANARIGeometry balls = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(balls, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-0.8f, 0.3f, 1.5f}, {0.0f, 0.3f, 0.0f}, {0.8f, 0.3f, -1.5f}}));
    s.set(balls, "radius", 0.3f);
    s.commit(balls);
    ANARISurface surface = s.surface(balls, s.matte({0.8f, 0.3f, 0.3f}));
    SUBCASE("depth of field: in focus at the middle sphere") {
        ANARICamera camera = s.perspective({0.0f, 1.2f, 4.0f}, {0.0f, 0.3f, 0.0f});
        s.set(camera, "apertureRadius", 0.15f);
        s.set(camera, "focusDistance", glm::length(glm::vec3(0.0f, 0.9f, 4.0f)));
        s.commit(camera);
        checkReference(s, "camera_depth_of_field", renderStage(s, {surface}, {}, camera));
    }
    SUBCASE("omnidirectional: the whole sphere of directions around a point above the floor") {
        ANARICamera camera = s.keep(anariNewCamera(s.device, "omnidirectional"));
        s.set(camera, "position", glm::vec3(0.0f, 1.0f, 1.0f));
        s.set(camera, "direction", glm::vec3(0.0f, 0.0f, -1.0f));
        s.set(camera, "up", glm::vec3(0.0f, 1.0f, 0.0f));
        s.commit(camera);
        checkReference(s, "camera_omnidirectional", renderStage(s, {surface}, {}, camera));
    }
}

TEST_CASE("channels: primitiveId, objectId, instanceId exact; albedo and normal of a flat matte quad") {
    RenderSession s;
    // Two quads side by side in one geometry (primitive ids 0 and 1), in a surface with id 7, placed by an
    // instance with id 42; the right half of the frame sees nothing.
    ANARIGeometry quads = s.keep(anariNewGeometry(s.device, "quad"));
    s.setObject(quads, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, -1, 0}, {-0.5f, -1, 0}, {-0.5f, 1, 0}, {-1, 1, 0},
                                                                    {-0.5f, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-0.5f, 1, 0}}));
    s.commit(quads);
    ANARISurface surface = s.surface(quads, s.matte({0.25f, 0.5f, 0.75f}));
    const uint32_t surfaceId = 7, instanceId = 42;
    s.setRaw(surface, "id", ANARI_UINT32, &surfaceId);
    s.commit(surface);
    ANARIWorld world = instancedWorld(s, "surface", ANARI_SURFACE, surface, instanceId);
    ANARIFrame frame = s.frame(world, frontCamera(s), s.renderer(1, 2), {8, 8}, ANARI_FLOAT32_VEC4);
    setChannel(s, frame, "channel.primitiveId", ANARI_UINT32);
    setChannel(s, frame, "channel.objectId", ANARI_UINT32);
    setChannel(s, frame, "channel.instanceId", ANARI_UINT32);
    setChannel(s, frame, "channel.albedo", ANARI_FLOAT32_VEC3);
    setChannel(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
    s.commit(frame);
    s.render(frame);
    const auto primitive = mapChannel<uint32_t>(s, frame, "channel.primitiveId", ANARI_UINT32);
    const auto object = mapChannel<uint32_t>(s, frame, "channel.objectId", ANARI_UINT32);
    const auto inst = mapChannel<uint32_t>(s, frame, "channel.instanceId", ANARI_UINT32);
    const auto albedo = mapChannel<glm::vec3>(s, frame, "channel.albedo", ANARI_FLOAT32_VEC3);
    const auto normal = mapChannel<glm::vec3>(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    // Pixel columns 0-1 see quad 0, 2-3 quad 1, 4-7 nothing.
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const size_t i = size_t(y) * 8 + x;
            INFO("pixel " << x << "," << y);
            const bool hit = x < 4;
            CHECK(primitive[i] == (hit ? x / 2 : kNoId));
            CHECK(object[i] == (hit ? surfaceId : kNoId));
            CHECK(inst[i] == (hit ? instanceId : kNoId));
            if (hit) {
                CHECK(glm::all(glm::lessThan(glm::abs(albedo[i] - glm::vec3(0.25f, 0.5f, 0.75f)), glm::vec3(1e-5f))));
                CHECK(glm::all(glm::lessThan(glm::abs(normal[i] - glm::vec3(0, 0, 1)), glm::vec3(1e-5f))));
            }
        }
}

TEST_CASE("vertex.cap closes cylinders and cones at the marked vertices only, overriding caps") {
    // A tube along -z from z = 0 to z = -2 (radius 0.5), seen straight down its axis by an orthographic
    // camera at z = 3: the central ray hits a cap at the near end at depth 3, else one at the far end (from
    // inside) at depth 5, else nothing (it runs along the open tube).
    for (const char* subtype : {"cylinder", "cone"}) {
        for (const auto& [caps, expected] : {std::pair{glm::uvec2(1, 0), 3.0f}, std::pair{glm::uvec2(0, 1), 5.0f},
                                             std::pair{glm::uvec2(1, 1), 3.0f},
                                             std::pair{glm::uvec2(0, 0), std::numeric_limits<float>::infinity()}}) {
            CAPTURE(subtype);
            CAPTURE(caps);
            RenderSession s;
            ANARIGeometry tube = s.keep(anariNewGeometry(s.device, subtype));
            s.setObject(tube, "vertex.position", ANARI_ARRAY1D,
                        s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0, 0, 0}, {0, 0, -2}}));
            if (std::string(subtype) == "cone")
                s.setObject(tube, "vertex.radius", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{0.5f, 0.5f}));
            else
                s.set(tube, "radius", 0.5f);
            s.setObject(tube, "vertex.cap", ANARI_ARRAY1D,
                        s.array(ANARI_UINT8, std::vector<uint8_t>{uint8_t(caps.x), uint8_t(caps.y)}));
            s.set(tube, "caps", "both");  // vertex.cap wins
            s.commit(tube);
            ANARICamera camera = frontCamera(s, 0.5f);
            const Image image = s.render(s.frame(s.world({s.surface(tube, s.matte(glm::vec3(0.5f)))}, {}), camera,
                                                 s.renderer(1, 1), {4, 4}, ANARI_FLOAT32_VEC4, true));
            CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
            for (const float depth : image.depth) {
                if (std::isinf(expected)) CHECK(std::isinf(depth));
                else CHECK(depth == doctest::Approx(expected).epsilon(1e-4));
            }
        }
    }
}

TEST_CASE("volume transferFunction1D over a structuredRegular field: transmittance through the API, exact type handling") {
    // A 2x2x2 UFIXED8 field of value 255 (1.0 after normalisation) spanning [-1, 1]^2 x [0, 1], a black
    // medium of opacity 1 - e^-1 over unitDistance 1: camera rays straight through it keep exp(-1) of the
    // white background. Also: the world's bounds include the volume, and nothing is reported, with
    // valueRange as the spec's FLOAT32_BOX1 or FLOAT64_BOX1, or as the FLOAT32_VEC2 that the SDK's CTS passes
    // (or FLOAT64_VEC2).
    for (const ANARIDataType rangeType : {ANARI_FLOAT32_BOX1, ANARI_FLOAT32_VEC2, ANARI_FLOAT64_BOX1, ANARI_FLOAT64_VEC2}) {
    CAPTURE(rangeType);
    RenderSession s;
    ANARISpatialField field = unitSlabField(s);
    ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
    s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
    s.set(volume, "color", glm::vec3(0.0f));
    s.set(volume, "opacity", 1.0f - std::exp(-1.0f));
    const float range[2] = {0.0f, 1.0f};
    const double range64[2] = {0.0, 1.0};
    const bool doubles = rangeType == ANARI_FLOAT64_BOX1 || rangeType == ANARI_FLOAT64_VEC2;
    s.setRaw(volume, "valueRange", rangeType, doubles ? static_cast<const void*>(range64) : range);
    s.commit(volume);
    ANARIWorld world = s.keep(anariNewWorld(s.device));
    s.setObject(world, "volume", ANARI_ARRAY1D, s.objects(ANARI_VOLUME, {volume}));
    s.commit(world);
    float bounds[6] = {};
    REQUIRE(anariGetProperty(s.device, world, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof(bounds), ANARI_WAIT));
    CHECK(bounds[0] == -1.0f);
    CHECK(bounds[5] == 1.0f);
    ANARICamera camera = frontCamera(s, 1.5f);
    ANARIRenderer renderer = s.renderer(256, 1, glm::vec4(1.0f));
    const float noAmbient = 0.0f;
    s.setRaw(renderer, "ambientRadiance", ANARI_FLOAT32, &noAmbient);
    s.commit(renderer);
    const Image image = s.render(s.frame(world, camera, renderer, {8, 8}, ANARI_FLOAT32_VEC4));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    double sum = 0.0;
    for (const glm::vec4& c : image.linear) sum += c.r;
    const double mean = sum / double(image.linear.size());
    // 64 pixels x 256 samples of a Bernoulli(e^-1): standard error 0.0038.
    CHECK(mean == doctest::Approx(std::exp(-1.0)).epsilon(0.05));
    }
}

// The slab's volume alone in a world, seen through at 8x8 and 256 samples against a white background with no
// ambient light (the transmittance tests below).
namespace {
ANARIFrame slabFrame(RenderSession& s, ANARIVolume volume) {
    ANARIWorld world = s.keep(anariNewWorld(s.device));
    s.setObject(world, "volume", ANARI_ARRAY1D, s.objects(ANARI_VOLUME, {volume}));
    s.commit(world);
    ANARIRenderer renderer = s.renderer(256, 1, glm::vec4(1.0f));
    const float noAmbient = 0.0f;
    s.setRaw(renderer, "ambientRadiance", ANARI_FLOAT32, &noAmbient);
    s.commit(renderer);
    return s.frame(world, frontCamera(s, 1.5f), renderer, {8, 8}, ANARI_FLOAT32_VEC4);
}
}  // namespace

// Where no 'opacity' is given, the colours' alpha is the opacity (pynari's samples give RGBA colour arrays
// and nothing else), and colours without alpha are opaque: the slab above, as a uniform FLOAT32_VEC4 and as
// an ARRAY1D of them, keeps exp(-1) of the background; black VEC3 colours with no opacity absorb all but
// e^-13.8 (opacity capped at 0.999999, docs/volumes.md). Before, no opacity meant an infinite extinction, and
// the volume was skipped.
TEST_CASE("volume: the colours' alpha is the opacity where none is given; none at all is opaque") {
    const float alpha = 1.0f - std::exp(-1.0f);
    struct Case {
        const char* name;
        double transmittance;
        std::function<void(RenderSession&, ANARIVolume)> colour;
    };
    for (const Case& c : {Case{"uniform VEC4", std::exp(-1.0),
                               [&](RenderSession& s, ANARIVolume v) { s.set(v, "color", glm::vec4(0, 0, 0, alpha)); }},
                          Case{"ARRAY1D of VEC4", std::exp(-1.0),
                               [&](RenderSession& s, ANARIVolume v) {
                                   s.setObject(v, "color", ANARI_ARRAY1D,
                                               s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>(2, glm::vec4(0, 0, 0, alpha))));
                               }},
                          Case{"VEC3, no opacity", 0.0,
                               [&](RenderSession& s, ANARIVolume v) { s.set(v, "color", glm::vec3(0.0f)); }}}) {
        CAPTURE(c.name);
        RenderSession s;
        ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
        s.setObject(volume, "value", ANARI_SPATIAL_FIELD, unitSlabField(s));
        c.colour(s, volume);
        const float range[2] = {0.0f, 1.0f};
        s.setRaw(volume, "valueRange", ANARI_FLOAT32_BOX1, range);
        s.commit(volume);
        const Image image = s.render(slabFrame(s, volume));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        double sum = 0.0;
        for (const glm::vec4& p : image.linear) sum += p.r;
        const double mean = sum / double(image.linear.size());
        // 64 pixels x 256 samples of a Bernoulli(e^-1): standard error 0.0038; e^-13.8 is 1e-6.
        if (c.transmittance > 0.0) CHECK(mean == doctest::Approx(c.transmittance).epsilon(0.05));
        else CHECK(mean < 1e-3);
    }
}

// The slab [-1, 1]^2 x [0, 1] as one hexahedron with one cell value (UFIXED8 255: 1.0), or as the same box
// cut into five tetrahedra with FLOAT32 values of 1 at the vertices; `edit` may break it before the commit.
namespace {
ANARISpatialField unstructuredSlab(RenderSession& s, bool tetrahedra,
                                   const std::function<void(RenderSession&, ANARISpatialField)>& edit = {}) {
    std::vector<glm::vec3> corners;
    for (int k = 0; k < 2; ++k)
        for (const glm::vec2 xy : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
            corners.emplace_back(xy, float(k));
    ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "unstructured"));
    s.setObject(field, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, corners));
    if (tetrahedra) {
        // The hexahedron's five-tetrahedron split: four corners cut off, and the one in the middle.
        const std::vector<uint32_t> index = {0, 1, 3, 4, 1, 2, 3, 6, 1, 5, 6, 4, 3, 6, 7, 4, 1, 3, 4, 6};
        s.setObject(field, "index", ANARI_ARRAY1D, s.array(ANARI_UINT32, index));
        s.setObject(field, "cell.index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{0, 4, 8, 12, 16}));
        s.setObject(field, "cell.type", ANARI_ARRAY1D, s.array(ANARI_UINT8, std::vector<uint8_t>(5, 10)));
        s.setObject(field, "vertex.data", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>(8, 1.0f)));
    } else {
        s.setObject(field, "index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
        s.setObject(field, "cell.index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{0}));
        s.setObject(field, "cell.type", ANARI_ARRAY1D, s.array(ANARI_UINT8, std::vector<uint8_t>{12}));
        s.setObject(field, "cell.data", ANARI_ARRAY1D, s.array(ANARI_UFIXED8, std::vector<uint8_t>{255}));
    }
    if (edit) edit(s, field);
    s.commit(field);
    return field;
}

ANARIVolume blackVolume(RenderSession& s, ANARISpatialField field) {
    ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
    s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
    s.set(volume, "color", glm::vec3(0.0f));
    s.set(volume, "opacity", 1.0f - std::exp(-1.0f));
    const float range[2] = {0.0f, 1.0f};
    s.setRaw(volume, "valueRange", ANARI_FLOAT32_BOX1, range);
    s.commit(volume);
    return volume;
}

// The mean red of a slab frame's pixels: the slab's transmittance against the white background.
double meanRed(const Image& image) {
    double sum = 0.0;
    for (const glm::vec4& p : image.linear) sum += p.r;
    return sum / double(image.linear.size());
}

// An edit that breaks a slab's field before its commit, and what the one error it gives must say.
struct BrokenField {
    const char* problem;
    std::function<void(RenderSession&, ANARISpatialField)> edit;
};
using SlabField = std::function<ANARISpatialField(RenderSession&, const std::function<void(RenderSession&, ANARISpatialField)>&)>;

// Each broken field makes exactly one error naming its problem, and the volume renders nothing: the white
// background shows in every pixel.
void checkRefused(const SlabField& slabField, const std::vector<BrokenField>& broken) {
    for (const BrokenField& b : broken) {
        CAPTURE(b.problem);
        RenderSession s;
        const Image image = s.render(slabFrame(s, blackVolume(s, slabField(s, b.edit))));
        CHECK_MESSAGE(s.log.count({b.problem}) == 1, s.log.dump());
        for (const glm::vec4& p : image.linear) CHECK(p.r == 1.0f);
    }
}
}  // namespace

// KHR_SPATIAL_FIELD_UNSTRUCTURED through the API: the slab as one hexahedron with a cell value and as five
// tetrahedra with vertex values keeps exp(-1) of the background, as the structuredRegular slab does, with
// nothing reported; broken meshes make the field invalid with one error naming the problem, and the volume
// renders nothing (the background shows).
TEST_CASE("volume over an unstructured field: transmittance through the API; broken meshes refused by name") {
    for (const bool tetrahedra : {false, true}) {
        CAPTURE(tetrahedra);
        RenderSession s;
        const Image image = s.render(slabFrame(s, blackVolume(s, unstructuredSlab(s, tetrahedra))));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        // 64 pixels x 256 samples of a Bernoulli(e^-1): standard error 0.0038.
        CHECK(meanRed(image) == doctest::Approx(std::exp(-1.0)).epsilon(0.05));
    }
    checkRefused([](RenderSession& s, const auto& edit) { return unstructuredSlab(s, false, edit); }, {
        {"index 3 is 9, past the 8 vertices",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{0, 1, 2, 9, 4, 5, 6, 7}));
         }},
        {"cell 0 has type 11",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "cell.type", ANARI_ARRAY1D, s.array(ANARI_UINT8, std::vector<uint8_t>{11}));
         }},
        {"cell 0's 8 indices from 4 run past the 8 of the index array",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "cell.index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{4}));
         }},
        {"cell 0's value is not finite",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "cell.data", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{NAN}));
         }},
        {"missing required parameter 'cell.type'",
         [](RenderSession& s, ANARISpatialField f) { anariUnsetParameter(s.device, f, "cell.type"); }},
        {"'vertex.position'",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>(8)));
         }},
    });
}

// KHR_SPATIAL_FIELD_NANOVDB through the API: a fog sphere made with NanoVDB's own tools, passed as an
// ARRAY1D of UINT8 and released at once, renders (the sphere's pixels are darker than the background, with
// nothing reported); a buffer with a broken magic number gives exactly one error naming it, and the background
// shows through.
TEST_CASE("volume over a nanovdb field: a fog sphere renders; a corrupt buffer is refused by name") {
    const auto handle = nanovdb::createFogVolumeSphere<float>(0.8f, nanovdb::Vec3f(0.0f, 0.0f, 0.5f), 0.05, 3.0);
    for (const bool corrupt : {false, true}) {
        CAPTURE(corrupt);
        RenderSession s;
        std::vector<uint8_t> bytes(handle.data(), handle.data() + handle.size());
        if (corrupt) bytes[1] ^= 0xFF;
        ANARIArray1D blob = anariNewArray1D(s.device, nullptr, nullptr, nullptr, ANARI_UINT8, bytes.size());
        std::memcpy(anariMapArray(s.device, blob), bytes.data(), bytes.size());
        anariUnmapArray(s.device, blob);
        ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "nanovdb"));
        s.setObject(field, "data", ANARI_ARRAY1D, blob);
        anariRelease(s.device, blob);  // released early: the field keeps what it needs
        s.commit(field);
        const Image image = s.render(slabFrame(s, blackVolume(s, field)));
        if (!corrupt) {
            // Iso-surfaces are not drawn in NanoVDB fields yet: refused by name (this crashed before it was).
            ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
            s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
            s.set(iso, "isovalue", 0.5f);
            s.commit(iso);
            CHECK_MESSAGE(s.log.count({"is a nanovdb field; iso-surfaces are drawn in"}) == 1, s.log.dump());
            s.log.clear();
        }
        if (corrupt) {
            CHECK_MESSAGE(s.log.count({"not a NanoVDB grid"}) == 1, s.log.dump());
            for (const glm::vec4& p : image.linear) CHECK(p.r == 1.0f);
        } else {
            CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
            size_t darker = 0;
            for (const glm::vec4& p : image.linear) darker += p.r < 0.9f ? 1 : 0;
            CHECK(darker > image.linear.size() / 4);
        }
    }
}

namespace {
using Box3i = std::array<int32_t, 6>;  // ANARI_INT32_BOX3: lower x y z, upper x y z

// The slab as an AMR hierarchy (spatial field "amr"): level 0, 4x4x4 cells of FLOAT32 1.0 over [-1, 1]^2 x
// [0, 1]; level 1, a UFIXED8 255 (1.0) block over its x < 0 half. The value arrays are released as soon as
// they are in block.data, the others once set. `edit` may break it before the commit.
ANARISpatialField amrSlab(RenderSession& s, const std::function<void(RenderSession&, ANARISpatialField)>& edit = {}) {
    ANARIArray3D coarse = anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32, 4, 4, 4);
    std::fill_n(static_cast<float*>(anariMapArray(s.device, coarse)), 64, 1.0f);
    anariUnmapArray(s.device, coarse);
    ANARIArray3D fine = anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_UFIXED8, 4, 8, 8);
    std::memset(anariMapArray(s.device, fine), 255, 4 * 8 * 8);
    anariUnmapArray(s.device, fine);
    ANARIArray1D data = anariNewArray1D(s.device, nullptr, nullptr, nullptr, ANARI_ARRAY3D, 2);
    auto* handles = static_cast<ANARIArray3D*>(anariMapArray(s.device, data));
    handles[0] = coarse;
    handles[1] = fine;
    anariUnmapArray(s.device, data);
    anariRelease(s.device, coarse);
    anariRelease(s.device, fine);
    ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "amr"));
    s.setObject(field, "block.data", ANARI_ARRAY1D, data);
    anariRelease(s.device, data);
    s.setObject(field, "cellWidth", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{1.0f, 0.5f}));
    s.setObject(field, "block.level", ANARI_ARRAY1D, s.array(ANARI_INT32, std::vector<int32_t>{0, 1}));
    s.setObject(field, "block.bounds", ANARI_ARRAY1D,
                s.array(ANARI_INT32_BOX3, std::vector<Box3i>{{0, 0, 0, 3, 3, 3}, {0, 0, 0, 3, 7, 7}}));
    s.set(field, "origin", glm::vec3(-1.0f, -1.0f, 0.0f));
    s.set(field, "spacing", glm::vec3(0.5f, 0.5f, 0.25f));
    if (edit) edit(s, field);
    s.commit(field);
    return field;
}
}  // namespace

// The ANARI "amr" field through the API: the slab as a two-level hierarchy keeps exp(-1) of the background
// with nothing reported; inconsistent hierarchies make the field invalid with one error naming the problem,
// and the background shows through.
TEST_CASE("volume over an amr field: transmittance through the API; inconsistent hierarchies refused by name") {
    {
        RenderSession s;
        const Image image = s.render(slabFrame(s, blackVolume(s, amrSlab(s))));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        // 64 pixels x 256 samples of a Bernoulli(e^-1): standard error 0.0038.
        CHECK(meanRed(image) == doctest::Approx(std::exp(-1.0)).epsilon(0.05));
    }
    checkRefused(amrSlab, {
        {"block 0 (level 1) [0 0 0 .. 1 1 1] and block 2 [1 1 1 .. 2 2 2] overlap",
         [](RenderSession& s, ANARISpatialField f) {
             ANARIArray3D extra = s.keep(anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32, 2, 2, 2));
             std::fill_n(static_cast<float*>(anariMapArray(s.device, extra)), 8, 1.0f);
             anariUnmapArray(s.device, extra);
             s.setObject(f, "block.data", ANARI_ARRAY1D, s.objects(ANARI_ARRAY3D, {extra, extra, extra}));
             s.setObject(f, "block.level", ANARI_ARRAY1D, s.array(ANARI_INT32, std::vector<int32_t>{1, 1, 1}));
             s.setObject(f, "block.bounds", ANARI_ARRAY1D,
                         s.array(ANARI_INT32_BOX3, std::vector<Box3i>{{0, 0, 0, 1, 1, 1}, {4, 4, 4, 5, 5, 5}, {1, 1, 1, 2, 2, 2}}));
         }},
        {"is 4x4x4 but its bounds hold 4x4x2 cells",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "block.bounds", ANARI_ARRAY1D,
                         s.array(ANARI_INT32_BOX3, std::vector<Box3i>{{0, 0, 0, 3, 3, 1}, {0, 0, 0, 3, 7, 7}}));
         }},
        {"lies outside the box of level 0's blocks",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "block.bounds", ANARI_ARRAY1D,
                         s.array(ANARI_INT32_BOX3, std::vector<Box3i>{{0, 0, 0, 3, 3, 3}, {8, 0, 0, 11, 7, 7}}));
         }},
        {"parameter 'block.bounds'",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "block.bounds", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>(12, 0.0f)));
         }},
        {"the cell width of level 1 (2.000000) is not below level 0's",
         [](RenderSession& s, ANARISpatialField f) {
             s.setObject(f, "cellWidth", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>{1.0f, 2.0f}));
         }},
        {"missing required parameter 'cellWidth'", [](RenderSession& s, ANARISpatialField f) { anariUnsetParameter(s.device, f, "cellWidth"); }},
    });
}

// A transfer-function edit (the volume's opacity set and committed) rebuilds the scene without uploading the
// field's voxels again, and the edit shows: the slab's transmittance follows the new opacity (the
// black absorber against a white background, as above). Committing the field again uploads them.
TEST_CASE("volume: a transfer-function edit reuses the field's voxels on the device; a field commit uploads them") {
    RenderSession s;
    ANARISpatialField field = unitSlabField(s);
    ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
    s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
    s.set(volume, "color", glm::vec3(0.0f));
    s.set(volume, "opacity", 1.0f - std::exp(-1.0f));
    s.commit(volume);
    ANARIFrame frame = slabFrame(s, volume);
    const auto counter = [&](const char* name) {
        uint64_t value = 99;
        CHECK(anariGetProperty(s.device, frame, name, ANARI_UINT64, &value, sizeof(value), ANARI_WAIT) == 1);
        return value;
    };
    const auto mean = [](const Image& image) {
        double sum = 0.0;
        for (const glm::vec4& c : image.linear) sum += c.r;
        return sum / double(image.linear.size());
    };
    const double before = mean(s.render(frame));
    CHECK(counter("ripple.volumeVoxelsUploaded") == 1);
    CHECK(counter("ripple.volumeVoxelsReused") == 0);
    s.set(volume, "opacity", 1.0f - std::exp(-2.0f));  // optical depth 2
    s.commit(volume);
    const double after = mean(s.render(frame));
    CHECK(s.sceneBuilds(frame) == 2);
    CHECK(counter("ripple.volumeVoxelsUploaded") == 0);
    CHECK(counter("ripple.volumeVoxelsReused") == 1);
    // 64 pixels x 256 samples of a Bernoulli(e^-d): standard errors 0.0038 and 0.0021.
    CHECK(before == doctest::Approx(std::exp(-1.0)).epsilon(0.05));
    CHECK(after == doctest::Approx(std::exp(-2.0)).epsilon(0.08));
    s.set(field, "spacing", glm::vec3(2.0f, 2.0f, 1.0f));
    s.commit(field);
    s.render(frame);
    CHECK(counter("ripple.volumeVoxelsUploaded") == 1);
    CHECK(counter("ripple.volumeVoxelsReused") == 0);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

// The quick-look renderer, analytic: a matte quad of colour c turned by theta from the view shows
// c * ambientColor * ambientRadiance * (1 - r + r |cos theta|), whatever the lights and maxPathLength; a
// black-backed volume of colour c and transmittance T shows E[colour at the first collision] = c (1 - T).
TEST_CASE("renderer eyeLight: the first surface lit from the eye, (1 - r + r |cos|), and volumes by their first collision") {
    const glm::vec3 c(0.8f, 0.5f, 0.2f);
    for (const float degrees : {0.0f, 60.0f}) {
        CAPTURE(degrees);
        RenderSession s;
        const float theta = glm::radians(degrees), x = 2.0f * std::cos(theta), z = 2.0f * std::sin(theta);
        ANARIGeometry quad = s.keep(anariNewGeometry(s.device, "quad"));
        s.setObject(quad, "vertex.position", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-x, -1.5f, z}, {x, -1.5f, -z}, {x, 1.5f, -z}, {-x, 1.5f, z}}));
        s.commit(quad);
        ANARIRenderer renderer = s.keep(anariNewRenderer(s.device, "eyeLight"));
        s.set(renderer, "ambientColor", glm::vec3(1.0f, 0.5f, 1.0f));
        s.set(renderer, "ambientRadiance", 2.0f);
        s.set(renderer, "eyeLightBlendRatio", 0.25f);
        s.setInt(renderer, "maxPathLength", 8);
        s.commit(renderer);
        const Image image = s.render(s.frame(s.world({s.surface(quad, s.matte(c))}, {s.directional({0, 0, -1}, 5.0f)}),
                                             frontCamera(s), renderer, {4, 4}, ANARI_FLOAT32_VEC4));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        const glm::vec3 expected = c * glm::vec3(2.0f, 1.0f, 2.0f) * (0.75f + 0.25f * std::cos(theta));
        for (const glm::vec4& p : image.linear) {
            INFO("pixel " << p.r << " " << p.g << " " << p.b);
            CHECK(glm::all(glm::lessThan(glm::abs(glm::vec3(p) - expected), glm::vec3(1e-5f))));
        }
    }
    {
        // The medium of the transmittance test above, coloured: opacity 1 - e^-1 across the unit depth.
        RenderSession s;
        ANARISpatialField field = floatField(s, {2, 2, 2}, std::vector<float>(8, 1.0f), {-1.0f, -1.0f, 0.0f}, {2.0f, 2.0f, 1.0f});
        ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
        s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
        s.set(volume, "color", c);
        s.set(volume, "opacity", 1.0f - std::exp(-1.0f));
        s.commit(volume);
        ANARIWorld world = s.keep(anariNewWorld(s.device));
        s.setObject(world, "volume", ANARI_ARRAY1D, s.objects(ANARI_VOLUME, {volume}));
        s.commit(world);
        ANARIRenderer renderer = s.keep(anariNewRenderer(s.device, "eyeLight"));
        s.setInt(renderer, "pixelSamples", 256);
        s.commit(renderer);
        const Image image = s.render(s.frame(world, frontCamera(s, 1.5f), renderer, {8, 8}, ANARI_FLOAT32_VEC4));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        glm::dvec3 sum(0.0);
        for (const glm::vec4& p : image.linear) sum += glm::dvec3(p);
        const glm::dvec3 mean = sum / double(image.linear.size());
        // 64 pixels x 256 samples of c times a Bernoulli(1 - e^-1): standard error 0.4% of the mean.
        for (int k = 0; k < 3; ++k) CHECK(mean[k] == doctest::Approx(c[k] * (1.0 - std::exp(-1.0))).epsilon(0.03));
    }
}

// KHR_FRAME_CHANNEL_OBJECT_ID and _INSTANCE_ID name volumes too: a medium dense enough that every camera ray
// through it scatters (opacity 0.999 over 0.001 units, the rays cross 1 unit) shows the volume's "id" and
// its instance's "id" where it covers the frame (pixels 2-5 of 8 each way), ~0u beside it (0 and 7).
TEST_CASE("channels: objectId and instanceId where a volume scatters") {
    RenderSession s;
    ANARISpatialField field = floatField(s, {2, 2, 2}, std::vector<float>(8, 1.0f), {-1.0f, -1.0f, 0.0f}, {2.0f, 2.0f, 1.0f});
    ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
    s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
    s.set(volume, "color", glm::vec3(0.5f));
    s.set(volume, "opacity", 0.999f);
    s.set(volume, "unitDistance", 0.001f);
    const uint32_t volumeId = 9, instanceId = 5;
    s.setRaw(volume, "id", ANARI_UINT32, &volumeId);
    s.commit(volume);
    ANARIWorld world = instancedWorld(s, "volume", ANARI_VOLUME, volume, instanceId);
    ANARIFrame frame = s.frame(world, frontCamera(s, 3.0f), s.renderer(1, 2), {8, 8}, ANARI_FLOAT32_VEC4);
    setChannel(s, frame, "channel.objectId", ANARI_UINT32);
    setChannel(s, frame, "channel.instanceId", ANARI_UINT32);
    s.commit(frame);
    s.render(frame);
    const auto object = mapChannel<uint32_t>(s, frame, "channel.objectId", ANARI_UINT32);
    const auto inst = mapChannel<uint32_t>(s, frame, "channel.instanceId", ANARI_UINT32);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            INFO("pixel " << x << "," << y);
            // Pixels 1 and 6 straddle the volume's edge at +-1 (a jittered ray may pass beside it): skipped.
            if (x == 1 || x == 6 || y == 1 || y == 6) continue;
            const bool inside = x >= 2 && x <= 5 && y >= 2 && y <= 5;
            CHECK(object[size_t(y) * 8 + x] == (inside ? volumeId : kNoId));
            CHECK(inst[size_t(y) * 8 + x] == (inside ? instanceId : kNoId));
        }
}

TEST_CASE("volume hostile input: each bad field or transfer function is reported, naming it, and renders nothing") {
    // Each case spoils one thing of a valid 2x2x2 field in a valid volume; the frame still renders (the
    // volume left out, so the white background shows through untouched) and the log names the problem.
    struct Case {
        const char* name;
        const char* expected;  // a fragment of the message
        std::function<void(RenderSession&, ANARISpatialField, ANARIVolume)> spoil;
    };
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<Case> cases = {
        {"NaN voxel", "not finite",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) {
             const float v[8] = {1, 1, 1, nan, 1, 1, 1, 1};
             s.setObject(f, "data", ANARI_ARRAY3D, array3D(s, ANARI_FLOAT32, {2, 2, 2}, v, sizeof(v)));
         }},
        {"Inf voxel", "not finite",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) {
             const float v[8] = {1, 1, 1, 1, 1, 1, 1, inf};
             s.setObject(f, "data", ANARI_ARRAY3D, array3D(s, ANARI_FLOAT32, {2, 2, 2}, v, sizeof(v)));
         }},
        {"zero dimension", "zero elements",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) {
             s.setObject(f, "data", ANARI_ARRAY3D, array3D(s, ANARI_FLOAT32, {2, 0, 2}, nullptr, 0));
         }},
        {"unsupported element type", "element type",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) {
             const int32_t v[8] = {};
             s.setObject(f, "data", ANARI_ARRAY3D, array3D(s, ANARI_INT32, {2, 2, 2}, v, sizeof(v)));
         }},
        {"data not a 3D array", "ARRAY3D",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) {
             s.setObject(f, "data", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>(8, 1.0f)));
         }},
        {"negative spacing", "spacing",
         [&](RenderSession& s, ANARISpatialField f, ANARIVolume) { s.set(f, "spacing", glm::vec3(1, -1, 1)); }},
        {"unitDistance 0", "unitDistance",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) { s.set(v, "unitDistance", 0.0f); }},
        {"NaN valueRange", "valueRange",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) {
             const float range[2] = {0.0f, nan};
             s.setRaw(v, "valueRange", ANARI_FLOAT32_BOX1, range);
         }},
        {"valueRange wider than float can map", "valueRange is wider",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) {
             const float range[2] = {-3e38f, 3e38f};
             s.setRaw(v, "valueRange", ANARI_FLOAT32_BOX1, range);
         }},
        {"valueRange too narrow for float", "valueRange is narrower",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) {
             const float range[2] = {0.0f, 1e-40f};
             s.setRaw(v, "valueRange", ANARI_FLOAT32_BOX1, range);
         }},
        {"extinction past float", "extinction above 1e36",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) {
             s.set(v, "opacity", 0.5f);
             s.set(v, "unitDistance", 1e-40f);
         }},
        {"NaN opacity", "opacity",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) { s.set(v, "opacity", nan); }},
        {"no field", "value",
         [&](RenderSession& s, ANARISpatialField, ANARIVolume v) { anariUnsetParameter(s.device, v, "value"); }},
    };
    for (const Case& c : cases) {
        const std::string name = c.name;
        CAPTURE(name);
        RenderSession s;
        const float ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};
        ANARISpatialField field = s.keep(anariNewSpatialField(s.device, "structuredRegular"));
        s.setObject(field, "data", ANARI_ARRAY3D, array3D(s, ANARI_FLOAT32, {2, 2, 2}, ones, sizeof(ones)));
        ANARIVolume volume = s.keep(anariNewVolume(s.device, "transferFunction1D"));
        s.setObject(volume, "value", ANARI_SPATIAL_FIELD, field);
        s.set(volume, "color", glm::vec3(0.0f));
        c.spoil(s, field, volume);
        s.commit(field);
        s.commit(volume);
        ANARIWorld world = s.keep(anariNewWorld(s.device));
        s.setObject(world, "volume", ANARI_ARRAY1D, s.objects(ANARI_VOLUME, {volume}));
        s.commit(world);
        ANARICamera camera = s.orthographic(glm::vec3(0.5f, 0.5f, 3.0f), glm::vec3(0, 0, -1));
        const Image image = s.render(s.frame(world, camera, s.renderer(2, 1, glm::vec4(1.0f)), {4, 4}, ANARI_FLOAT32_VEC4));
        CHECK_MESSAGE(s.log.count({c.expected}) >= 1, s.log.dump());
        for (const glm::vec4& p : image.linear) CHECK(p.r == 1.0f);  // nothing of the spoilt volume rendered
    }
}

TEST_CASE("isosurface: exact crossing of the trilinear interpolant, its gradient as normal, the isovalue as primitive id") {
    // f(x, y, z) = x y z sampled on a 5^3 grid over the unit cube: trilinear in every cell, so the
    // interpolant is f itself and the surfaces f = c are known exactly. Seen straight down from z = 3, the ray
    // at (x, y) meets f = c at z = c / (x y) when x y > c: the higher isovalue first.
    const std::vector<float> isovalues = {0.125f, 0.3f};
    RenderSession s;
    ANARISpatialField field = xyzField(s);
    ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
    s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
    s.setObject(iso, "isovalue", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, isovalues));
    s.commit(iso);
    ANARICamera camera = s.orthographic(glm::vec3(0.5f, 0.5f, 3.0f), glm::vec3(0, 0, -1));
    const uint32_t size = 16;
    ANARIFrame frame = s.frame(s.world({s.surface(iso, s.matte(glm::vec3(0.5f)))}, {}), camera, s.renderer(1, 1),
                               {size, size}, ANARI_FLOAT32_VEC4, true);
    setChannel(s, frame, "channel.primitiveId", ANARI_UINT32);
    setChannel(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
    s.commit(frame);
    const Image image = s.render(frame);
    const auto primitive = mapChannel<uint32_t>(s, frame, "channel.primitiveId", ANARI_UINT32);
    const auto normal = mapChannel<glm::vec3>(s, frame, "channel.normal", ANARI_FLOAT32_VEC3);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    uint32_t checked[3] = {0, 0, 0};  // pixels that see nothing, the lower and the higher surface
    for (uint32_t py = 0; py < size; ++py)
        for (uint32_t px = 0; px < size; ++px) {
            const float x = (px + 0.5f) / size, y = (py + 0.5f) / size, xy = x * y;
            const size_t i = size_t(py) * size + px;
            INFO("pixel " << px << "," << py);
            int surface = -1;
            for (int k = 0; k < 2; ++k)
                if (xy > isovalues[k]) surface = k;
            // Samples are jittered within the pixel: skip pixels whose footprint holds an edge.
            const float h = 0.5f / size, xyLow = (x - h) * (y - h), xyHigh = (x + h) * (y + h);
            bool nearEdge = false;
            for (float c : isovalues) nearEdge = nearEdge || (xyLow <= c && c <= xyHigh);
            if (nearEdge) continue;
            if (surface < 0) {
                CHECK(std::isinf(image.depth[i]));
                CHECK(primitive[i] == kNoId);
                ++checked[0];
                continue;
            }
            // The sample's position in the pixel is jittered, so the hit is checked for consistency with the
            // exact surface: its height from the depth, its x and y from the normal (parallel to the gradient
            // (yz, xz, xy), so x = z n.z / n.x and y = z n.z / n.y), and those must lie on f = c in the pixel.
            CHECK(primitive[i] == uint32_t(surface));
            const float z = 3.0f - image.depth[i];
            const glm::vec3 nrm = normal[i];
            REQUIRE(nrm.x > 0.0f);
            REQUIRE(nrm.y > 0.0f);
            const float hx = z * nrm.z / nrm.x, hy = z * nrm.z / nrm.y;
            CHECK(hx * hy * z == doctest::Approx(isovalues[surface]).epsilon(1e-4));
            CHECK(std::abs(hx - x) <= 0.5f / size + 1e-4f);
            CHECK(std::abs(hy - y) <= 0.5f / size + 1e-4f);
            CHECK(glm::length(nrm) == doctest::Approx(1.0f).epsilon(1e-5));
            ++checked[surface + 1];
        }
    CHECK(checked[0] > 20);  // each case is seen by enough pixels to mean something
    CHECK(checked[1] > 20);
    CHECK(checked[2] > 20);
}

// Attributes as KHR_GEOMETRY_ISOSURFACE lists them: "primitive.attributeN" holds one value per isovalue,
// the uniform "attributeN" one for all; a matte material reading the attribute shows it as the albedo of
// each surface. Same field and view as above.
TEST_CASE("isosurface: per-isovalue and uniform attributes reach the material") {
    const std::vector<float> isovalues = {0.125f, 0.3f};
    const std::vector<glm::vec4> perIsovalue = {{0.9f, 0.1f, 0.2f, 1.0f}, {0.1f, 0.3f, 0.8f, 1.0f}};
    const glm::vec4 uniform(0.2f, 0.7f, 0.4f, 1.0f);
    for (const bool perPrimitive : {true, false}) {
        CAPTURE(perPrimitive);
        RenderSession s;
        ANARISpatialField field = xyzField(s);
        ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
        s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
        s.setObject(iso, "isovalue", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, isovalues));
        if (perPrimitive) s.setObject(iso, "primitive.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, perIsovalue));
        else s.set(iso, "attribute2", uniform);
        s.commit(iso);
        ANARIMaterial material = s.keep(anariNewMaterial(s.device, "matte"));
        anariSetParameter(s.device, material, "color", ANARI_STRING, perPrimitive ? "attribute1" : "attribute2");
        s.commit(material);
        ANARICamera camera = s.orthographic(glm::vec3(0.5f, 0.5f, 3.0f), glm::vec3(0, 0, -1));
        const uint32_t size = 16;
        ANARIFrame frame = s.frame(s.world({s.surface(iso, material)}, {}), camera, s.renderer(1, 1), {size, size},
                                   ANARI_FLOAT32_VEC4, true);
        setChannel(s, frame, "channel.primitiveId", ANARI_UINT32);
        setChannel(s, frame, "channel.albedo", ANARI_FLOAT32_VEC3);
        s.commit(frame);
        s.render(frame);
        const auto primitive = mapChannel<uint32_t>(s, frame, "channel.primitiveId", ANARI_UINT32);
        const auto albedo = mapChannel<glm::vec3>(s, frame, "channel.albedo", ANARI_FLOAT32_VEC3);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        uint32_t seen[2] = {0, 0};
        for (size_t i = 0; i < size_t(size) * size; ++i) {
            if (primitive[i] == kNoId) continue;
            REQUIRE(primitive[i] < 2);
            const glm::vec3 expected = perPrimitive ? glm::vec3(perIsovalue[primitive[i]]) : glm::vec3(uniform);
            INFO("pixel " << i << " on isovalue " << primitive[i]);
            CHECK(glm::length(albedo[i] - expected) < 1e-5f);
            ++seen[primitive[i]];
        }
        CHECK(seen[0] > 20);
        CHECK(seen[1] > 20);
    }
}

TEST_CASE("isosurface hostile input: a missing field or isovalue, a NaN isovalue, the wrong element type") {
    struct Case {
        const char* name;
        const char* expected;
        std::function<void(RenderSession&, ANARIGeometry)> spoil;
    };
    const std::vector<Case> cases = {
        {"no field", "field", [](RenderSession& s, ANARIGeometry g) { anariUnsetParameter(s.device, g, "field"); }},
        {"no isovalue", "isovalue", [](RenderSession& s, ANARIGeometry g) { anariUnsetParameter(s.device, g, "isovalue"); }},
        {"NaN isovalue", "not finite",
         [](RenderSession& s, ANARIGeometry g) { s.set(g, "isovalue", std::numeric_limits<float>::quiet_NaN()); }},
        {"INT32 isovalues", "must be FLOAT32 or an ARRAY1D of FLOAT32",
         [](RenderSession& s, ANARIGeometry g) { s.setObject(g, "isovalue", ANARI_ARRAY1D, s.array(ANARI_INT32, std::vector<int32_t>{1})); }},
        {"empty isovalue array (refused when made)", "zero elements",
         [](RenderSession& s, ANARIGeometry g) {
             s.setObject(g, "isovalue", ANARI_ARRAY1D, s.keep(anariNewArray1D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32, 0)));
         }},
    };
    for (const Case& c : cases) {
        const std::string name = c.name;
        CAPTURE(name);
        RenderSession s;
        ANARISpatialField field = floatField(s, glm::uvec3(2), {0, 1, 0, 1, 0, 1, 0, 1});
        ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
        s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
        s.set(iso, "isovalue", 0.5f);
        c.spoil(s, iso);
        s.commit(iso);
        ANARICamera camera = s.orthographic(glm::vec3(0.5f, 0.5f, 3.0f), glm::vec3(0, 0, -1));
        const Image image = s.render(s.frame(s.world({s.surface(iso, s.matte(glm::vec3(0.5f)))}, {}), camera,
                                             s.renderer(1, 1, glm::vec4(1.0f)), {4, 4}, ANARI_FLOAT32_VEC4));
        CHECK_MESSAGE(s.log.count({c.expected}) >= 1, s.log.dump());
        for (const glm::vec4& p : image.linear) CHECK(p.r == 1.0f);  // nothing of the spoilt surface rendered
    }
}

TEST_CASE("isosurface: no ray leaks through a closed surface across cell faces, edges and corners") {
    // f = |p - c|^2 on a 9^3 grid centred on c, surface f = 0.5: a closed, nearly spherical surface of radius
    // about 0.707 whose crossings land on every kind of cell boundary. Seen from outside with 64x64 rays,
    // every ray that passes within 0.6 of the centre must hit it, and none beyond 0.75 may. Two grids: one
    // whose cell faces are exact in float (spacing 0.25 from -1), one whose faces round differently when
    // computed from either neighbouring cell (spacing 0.2431 from an odd origin).
    const uint32_t n = 9;
    struct Grid {
        glm::vec3 origin;
        float spacing;
    };
    for (const Grid grid : {Grid{glm::vec3(-1.0f), 0.25f}, Grid{glm::vec3(-0.9863f, -1.0071f, -0.9937f), 0.2431f}}) {
        const glm::vec3 centre = grid.origin + glm::vec3(4.0f * grid.spacing);
        std::vector<float> voxels;
        for (uint32_t k = 0; k < n; ++k)
            for (uint32_t j = 0; j < n; ++j)
                for (uint32_t i = 0; i < n; ++i) {
                    const glm::vec3 p = grid.origin + glm::vec3(i, j, k) * grid.spacing - centre;
                    voxels.push_back(glm::dot(p, p));
                }
        for (const glm::vec3 direction : {glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, 1, -1))}) {
            CAPTURE(grid.spacing);
            CAPTURE(direction);
            RenderSession s;
            ANARISpatialField field = floatField(s, glm::uvec3(n), voxels, grid.origin, glm::vec3(grid.spacing));
            ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
            s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
            s.set(iso, "isovalue", 0.5f);
            s.commit(iso);
            ANARICamera camera = s.orthographic(centre - 3.0f * direction, direction, 2.0f);
            const uint32_t size = 64;
            const Image image = s.render(s.frame(s.world({s.surface(iso, s.matte(glm::vec3(0.5f)))}, {}), camera,
                                                 s.renderer(4, 1), {size, size}, ANARI_FLOAT32_VEC4, true));
            CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
            uint32_t inside = 0, outside = 0;
            for (uint32_t py = 0; py < size; ++py)
                for (uint32_t px = 0; px < size; ++px) {
                    // Distance of the pixel's rays from the axis through the centre (within half a pixel).
                    const float r = glm::length(glm::vec2(px + 0.5f, py + 0.5f) / float(size) * 2.0f - 1.0f);
                    const float depth = image.depth[size_t(py) * size + px];
                    INFO("pixel " << px << "," << py << " r " << r);
                    if (r < 0.6f) {
                        CHECK(std::isfinite(depth));
                        ++inside;
                    } else if (r > 0.75f) {
                        CHECK(std::isinf(depth));
                        ++outside;
                    }
                }
            CHECK(inside > 1000);
            CHECK(outside > 1000);
        }
    }
}

TEST_CASE("isosurface: the Marschner-Lobb surface at 0.5 against its reference image") {
    // The test signal of Marschner & Lobb (1994; alpha 0.25, f_M 6) on a 41^3 grid over the box
    // [-0.8, 0.8] x [0.05, 1.65] x [-0.8, 0.8] (its z axis turned up), surface at 0.5, over the floor: a
    // regression check of the whole path (cells, roots, normals, shading and shadows), metric as for the
    // other references (RMSE of the sRGB image).
    RenderSession s;
    const uint32_t n = 41;
    std::vector<float> voxels;
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                const glm::vec3 p = glm::vec3(i, j, k) / float(n - 1) * 2.0f - 1.0f;  // (x, up, z)
                const float r = std::sqrt(p.x * p.x + p.z * p.z), pi = 3.14159265f;
                const float rho = std::cos(2.0f * pi * 6.0f * std::cos(pi * r / 2.0f));
                voxels.push_back((1.0f - std::sin(pi * p.y / 2.0f) + 0.25f * (1.0f + rho)) / 2.5f);
            }
    ANARISpatialField field = floatField(s, glm::uvec3(n), voxels, glm::vec3(-0.8f, 0.05f, -0.8f), glm::vec3(1.6f / (n - 1)));
    ANARIGeometry iso = s.keep(anariNewGeometry(s.device, "isosurface"));
    s.setObject(iso, "field", ANARI_SPATIAL_FIELD, field);
    s.set(iso, "isovalue", 0.5f);
    s.commit(iso);
    checkReference(s, "isosurface_marschner_lobb", renderStage(s, {s.surface(iso, s.matte(glm::vec3(0.8f, 0.6f, 0.3f)))}));
}
