// Render tests of the sampler modes beyond image1D/2D at attribute0: inAttribute selecting another vertex
// attribute, the transform and primitive samplers, and image3D (nearest and trilinear). Each drives the
// emission of a quad seen straight on with no lights and one bounce, so a pixel is exactly the sampler's
// output where the output is constant over the pixel (checked to 1e-4), or within the output's change
// across a pixel (camera rays are jittered) where it varies.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <cstring>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

constexpr float kExact = 1e-4f;

// A 2x2 grid of quads covering [-1, 1]^2 in z = 0, numbered row by row from the bottom left, with
// per-vertex attribute0 = (u, v) over the whole grid and attribute2 = (1 - u, v, 0.75) (mirrored u).
ANARIGeometry quadGrid(RenderSession& s) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uv;
    std::vector<glm::vec3> mirrored;
    for (int q = 0; q < 4; ++q) {
        const glm::vec2 lower(float(q % 2) - 1.0f, float(q / 2) - 1.0f);
        for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
            const glm::vec2 p = lower + corner;
            positions.emplace_back(p, 0.0f);
            uv.push_back(0.5f * (p + 1.0f));
            mirrored.emplace_back(1.0f - uv.back().x, uv.back().y, 0.75f);
        }
    }
    ANARIGeometry grid = s.keep(anariNewGeometry(s.device, "quad"));
    s.setObject(grid, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, positions));
    s.setObject(grid, "vertex.attribute0", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC2, uv));
    s.setObject(grid, "vertex.attribute2", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, mirrored));
    s.commit(grid);
    return grid;
}

// The emission each pixel of an orthographic, straight-on view of the grid sees (float channel).
Image renderEmission(RenderSession& s, ANARISampler emissive, glm::uvec2 size) {
    ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.setObject(material, "emissive", ANARI_SAMPLER, emissive);
    s.commit(material);
    ANARICamera camera = s.orthographic(glm::vec3(0, 0, 3), glm::vec3(0, 0, -1), 2.0f);
    ANARIFrame frame = s.frame(s.world({s.surface(quadGrid(s), material)}, {}), camera,
                               s.renderer(1, 1, glm::vec4(0, 0, 0, 1)), size, ANARI_FLOAT32_VEC4);
    Image image = s.render(frame);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    return image;
}

ANARISampler committed(RenderSession& s, ANARISampler sampler) {
    s.commit(sampler);
    return sampler;
}

bool near(glm::vec3 got, glm::vec3 expected, float tolerance) {
    return glm::all(glm::lessThanEqual(glm::abs(got - expected), glm::vec3(tolerance)));
}

}  // namespace

TEST_CASE("primitive sampler: each quad shows array entry (primitive id + inOffset), exactly") {
    RenderSession s;
    const std::vector<glm::vec4> colors{{9, 9, 9, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1}};
    ANARISampler sampler = s.keep(anariNewSampler(s.device, "primitive"));
    s.setObject(sampler, "array", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, colors));
    const uint64_t offset = 1;
    s.setRaw(sampler, "inOffset", ANARI_UINT64, &offset);
    const Image image = renderEmission(s, committed(s, sampler), {8, 8});
    // Quad q (row by row from the bottom left, as are frame rows) covers a 4x4 block of pixels.
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            INFO("pixel " << x << "," << y);
            CHECK(near(glm::vec3(image.at(x, y)), glm::vec3(colors[1 + (y / 4) * 2 + x / 4]), kExact));
        }
}

TEST_CASE("transform sampler: outTransform * attribute2 + outOffset, analytic") {
    RenderSession s;
    ANARISampler sampler = s.keep(anariNewSampler(s.device, "transform"));
    s.set(sampler, "inAttribute", "attribute2");
    glm::mat4 out(0.0f);
    out[0] = glm::vec4(0, 2, 0, 0);  // attribute x (1 - u) -> green, doubled
    out[1] = glm::vec4(1, 0, 0, 0);  // attribute y (v) -> red
    out[2] = glm::vec4(0, 0, 1, 0);  // attribute z (0.75) -> blue
    s.setRaw(sampler, "outTransform", ANARI_FLOAT32_MAT4, &out);
    s.set(sampler, "outOffset", glm::vec4(0.0f, 0.0f, 0.125f, 0.0f));
    const Image image = renderEmission(s, committed(s, sampler), {16, 16});
    // Over a pixel u and v change by 1/16, so green by 2/16 and red by 1/16 from the pixel centre's value.
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            const float u = (float(x) + 0.5f) / 16.0f, v = (float(y) + 0.5f) / 16.0f;
            const glm::vec3 got(image.at(x, y));
            INFO("pixel " << x << "," << y << " got " << got.r << " " << got.g << " " << got.b);
            CHECK(std::abs(got.r - v) <= 1.0f / 32.0f + kExact);
            CHECK(std::abs(got.g - 2.0f * (1.0f - u)) <= 2.0f / 32.0f + kExact);
            CHECK(std::abs(got.b - 0.875f) <= kExact);
        }
}

TEST_CASE("image2D sampler reading inAttribute attribute2 (u mirrored), nearest: exact texels") {
    RenderSession s;
    const std::vector<glm::vec4> texels{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    ANARIArray2D image = s.keep(anariNewArray2D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, 2, 2));
    std::memcpy(anariMapArray(s.device, image), texels.data(), texels.size() * sizeof(glm::vec4));
    anariUnmapArray(s.device, image);
    ANARISampler sampler = s.keep(anariNewSampler(s.device, "image2D"));
    s.setObject(sampler, "image", ANARI_ARRAY2D, image);
    s.set(sampler, "filter", "nearest");
    s.set(sampler, "inAttribute", "attribute2");
    const Image rendered = renderEmission(s, committed(s, sampler), {8, 8});
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            INFO("pixel " << x << "," << y);
            CHECK(near(glm::vec3(rendered.at(x, y)), glm::vec3(texels[(y / 4) * 2 + (1 - x / 4)]), kExact));
        }
}

TEST_CASE("image3D sampler: nearest picks the slice at w (with inOffset); linear blends slices") {
    RenderSession s;
    // 2x2x2 texels: slice 0 red/green/blue/white, slice 1 the same times 4.
    std::vector<glm::vec4> texels{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    for (int i = 0; i < 4; ++i) texels.push_back(glm::vec4(glm::vec3(texels[i]) * 4.0f, 1.0f));
    ANARIArray3D volume = s.keep(anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, 2, 2, 2));
    std::memcpy(anariMapArray(s.device, volume), texels.data(), texels.size() * sizeof(glm::vec4));
    anariUnmapArray(s.device, volume);
    // attribute2 is (1 - u, v, 0.75): w = 0.75 lies in slice 1, and 0.25 (inOffset -0.5) in slice 0.
    for (const float offset : {0.0f, -0.5f}) {
        CAPTURE(offset);
        ANARISampler sampler = s.keep(anariNewSampler(s.device, "image3D"));
        s.setObject(sampler, "image", ANARI_ARRAY3D, volume);
        s.set(sampler, "filter", "nearest");
        s.set(sampler, "inAttribute", "attribute2");
        s.set(sampler, "inOffset", glm::vec4(0.0f, 0.0f, offset, 0.0f));
        const Image image = renderEmission(s, committed(s, sampler), {8, 8});
        const int slice = offset == 0.0f ? 1 : 0;
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                INFO("pixel " << x << "," << y);
                CHECK(near(glm::vec3(image.at(x, y)), glm::vec3(texels[slice * 4 + (y / 4) * 2 + (1 - x / 4)]), kExact));
            }
    }
    // Linear: in a 1x1x2 image (black, white), w = 0.75 + inOffset = 0.375 sits a quarter of the way from
    // the centre of slice 0 (w 0.25) to that of slice 1 (w 0.75): exactly 0.25 grey.
    const std::vector<glm::vec4> ends{{0, 0, 0, 1}, {1, 1, 1, 1}};
    ANARIArray3D ramp = s.keep(anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, 1, 1, 2));
    std::memcpy(anariMapArray(s.device, ramp), ends.data(), ends.size() * sizeof(glm::vec4));
    anariUnmapArray(s.device, ramp);
    ANARISampler linear = s.keep(anariNewSampler(s.device, "image3D"));
    s.setObject(linear, "image", ANARI_ARRAY3D, ramp);
    s.set(linear, "inAttribute", "attribute2");
    s.set(linear, "inOffset", glm::vec4(0.0f, 0.0f, -0.375f, 0.0f));
    const Image blended = renderEmission(s, committed(s, linear), {4, 4});
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) {
            INFO("pixel " << x << "," << y);
            CHECK(near(glm::vec3(blended.at(x, y)), glm::vec3(0.25f), kExact));
        }
}

TEST_CASE("material parameters named by attribute: emissive = attribute2 shows the attribute, analytic") {
    RenderSession s;
    ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.set(material, "emissive", "attribute2");
    s.commit(material);
    ANARICamera camera = s.keep(anariNewCamera(s.device, "orthographic"));
    s.set(camera, "position", glm::vec3(0, 0, 3));
    s.set(camera, "direction", glm::vec3(0, 0, -1));
    s.set(camera, "height", 2.0f);
    s.commit(camera);
    const glm::uvec2 size{16, 16};
    const Image image = s.render(s.frame(s.world({s.surface(quadGrid(s), material)}, {}), camera,
                                         s.renderer(1, 1, glm::vec4(0, 0, 0, 1)), size, ANARI_FLOAT32_VEC4));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    // attribute2 is (1 - u, v, 0.75); over a pixel u and v change by 1/16 from the pixel centre's value.
    for (uint32_t y = 0; y < size.y; ++y)
        for (uint32_t x = 0; x < size.x; ++x) {
            const float u = (float(x) + 0.5f) / 16.0f, v = (float(y) + 0.5f) / 16.0f;
            const glm::vec3 got(image.at(x, y));
            INFO("pixel " << x << "," << y << " got " << got.r << " " << got.g << " " << got.b);
            CHECK(std::abs(got.r - (1.0f - u)) <= 1.0f / 32.0f + kExact);
            CHECK(std::abs(got.g - v) <= 1.0f / 32.0f + kExact);
            CHECK(std::abs(got.b - 0.75f) <= kExact);
        }
}

TEST_CASE("material parameters named by attribute: metallic, roughness, baseColor and opacity as the values") {
    // A lit floor whose vertex attributes hold constant values: naming the attributes must give the image
    // of the same values set directly (the texture path multiplies 1 by the attribute: no rounding), and
    // the values must matter (metallic 0 instead of 1 changes the image).
    const glm::vec3 baseColor(0.9f, 0.5f, 0.2f);
    auto render = [&](bool fromAttributes, float metallic) {
        RenderSession s;
        ANARIGeometry floor = s.floor();
        const size_t vertices = 4;
        s.setObject(floor, "vertex.attribute0", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32, std::vector<float>(vertices, metallic)));
        s.setObject(floor, "vertex.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>(vertices, 0.35f)));
        s.setObject(floor, "vertex.attribute2", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>(vertices, baseColor)));
        s.setObject(floor, "vertex.attribute3", ANARI_ARRAY1D, s.array(ANARI_FLOAT32, std::vector<float>(vertices, 1.0f)));
        s.commit(floor);
        ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
        if (fromAttributes) {
            s.set(material, "metallic", "attribute0");
            s.set(material, "roughness", "attribute1");
            s.set(material, "baseColor", "attribute2");
            s.set(material, "opacity", "attribute3");
        } else {
            s.set(material, "metallic", metallic);
            s.set(material, "roughness", 0.35f);
            s.set(material, "baseColor", baseColor);
            s.set(material, "opacity", 1.0f);
        }
        s.commit(material);
        const Image image = s.render(s.frame(s.world({s.surface(floor, material)}, {s.directional({-0.3f, -1, -0.2f}, 2.0f)}),
                                             s.perspective({0, 3, 4}, {0, 0, 0}), s.renderer(4, 3), {24, 24},
                                             ANARI_FLOAT32_VEC4));
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        return image;
    };
    const Image named = render(true, 1.0f);
    CHECK(ripple::test::rmseRgb(named, render(false, 1.0f)) <= 1e-6);
    CHECK(ripple::test::rmseRgb(named, render(true, 0.0f)) > 1e-2);
}

namespace {

// The emission of a physicallyBased material whose "emissive" names `attribute`, seen straight on down -z
// through an orthographic view 2 units tall, no lights, one bounce: each pixel is the attribute's value
// there. `place` makes the world's instance of the surface (nullptr: the surface straight in the world).
Image renderAttribute(RenderSession& s, ANARIGeometry geometry, const char* attribute, glm::uvec2 size,
                      ANARIInstance (*place)(RenderSession&, ANARISurface) = nullptr) {
    ANARIMaterial material = s.keep(anariNewMaterial(s.device, "physicallyBased"));
    s.set(material, "baseColor", glm::vec3(0.0f));
    s.set(material, "emissive", attribute);
    s.commit(material);
    ANARISurface surface = s.surface(geometry, material);
    ANARIWorld world = s.world({}, {});
    if (place) {
        ANARIInstance instance = place(s, surface);
        s.setObject(world, "instance", ANARI_ARRAY1D, s.objects(ANARI_INSTANCE, {instance}));
    } else {
        s.setObject(world, "surface", ANARI_ARRAY1D, s.objects(ANARI_SURFACE, {surface}));
    }
    s.commit(world);
    ANARICamera camera = s.orthographic(glm::vec3(0, 0, 3), glm::vec3(0, 0, -1), 2.0f);
    Image image = s.render(s.frame(world, camera, s.renderer(1, 1, glm::vec4(0, 0, 0, 1)), size, ANARI_FLOAT32_VEC4));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    return image;
}

// Two spheres of radius 0.5 side by side, filling the view's middle row.
ANARIGeometry twoSpheres(RenderSession& s) {
    ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(geometry, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-0.5f, 0, 0}, {0.5f, 0, 0}}));
    s.set(geometry, "radius", 0.5f);
    return geometry;
}

}  // namespace

// The attribute rules of the spec: per vertex before per primitive before the geometry's uniform value, on
// every geometry; an instance's uniform attribute (and colour) replaces the geometry's on that instance.
TEST_CASE("attributes: per vertex, per primitive and uniform on spheres, quads and cylinders; instance values replace them") {
    const glm::vec4 left(0.2f, 0.4f, 0.6f, 1.0f), right(0.9f, 0.7f, 0.1f, 1.0f);
    SUBCASE("sphere vertex.attribute1: one value per sphere") {
        RenderSession s;
        ANARIGeometry geometry = twoSpheres(s);
        s.setObject(geometry, "vertex.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.setObject(geometry, "primitive.attribute1", ANARI_ARRAY1D,  // per vertex wins
                    s.array(ANARI_FLOAT32_VEC4, std::vector<glm::vec4>(2, glm::vec4(5.0f))));
        s.commit(geometry);
        const Image image = renderAttribute(s, geometry, "attribute1", {8, 8});
        CHECK(near(glm::vec3(image.at(2, 4)), glm::vec3(left), kExact));
        CHECK(near(glm::vec3(image.at(5, 4)), glm::vec3(right), kExact));
    }
    SUBCASE("sphere primitive.attribute3 with primitive.index: per sphere, not per vertex") {
        RenderSession s;
        ANARIGeometry geometry = twoSpheres(s);
        s.setObject(geometry, "primitive.index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{1, 0}));
        s.setObject(geometry, "primitive.attribute3", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.commit(geometry);
        const Image image = renderAttribute(s, geometry, "attribute3", {8, 8});
        CHECK(near(glm::vec3(image.at(2, 4)), glm::vec3(right), kExact));  // sphere 1 sits on vertex 0
        CHECK(near(glm::vec3(image.at(5, 4)), glm::vec3(left), kExact));
    }
    SUBCASE("quad primitive.attribute0 (one per quad, not per triangle) and a uniform attribute1") {
        RenderSession s;
        ANARIGeometry grid = s.keep(anariNewGeometry(s.device, "quad"));
        s.setObject(grid, "vertex.position", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0},
                                                                       {0, -1, 0}, {1, -1, 0}, {1, 1, 0}, {0, 1, 0}}));
        s.setObject(grid, "primitive.attribute0", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC2, std::vector<glm::vec2>{{0.25f, 0.5f}, {0.75f, 0.125f}}));
        s.set(grid, "attribute1", right);
        s.commit(grid);
        const Image image = renderAttribute(s, grid, "attribute0", {8, 8});
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                INFO("pixel " << x << "," << y);
                CHECK(near(glm::vec3(image.at(x, y)), x < 4 ? glm::vec3(0.25f, 0.5f, 0) : glm::vec3(0.75f, 0.125f, 0), kExact));
            }
        const Image uniform = renderAttribute(s, grid, "attribute1", {4, 4});
        CHECK(near(glm::vec3(uniform.at(1, 2)), glm::vec3(right), kExact));
    }
    SUBCASE("sphere vertex.attribute1 with primitive.index: the vertex's value") {
        RenderSession s;
        ANARIGeometry geometry = twoSpheres(s);
        s.setObject(geometry, "primitive.index", ANARI_ARRAY1D, s.array(ANARI_UINT32, std::vector<uint32_t>{1}));
        s.setObject(geometry, "vertex.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.commit(geometry);
        const Image image = renderAttribute(s, geometry, "attribute1", {8, 8});
        CHECK(near(glm::vec3(image.at(5, 4)), glm::vec3(right), kExact));  // the one sphere sits on vertex 1
        CHECK(near(glm::vec3(image.at(2, 4)), glm::vec3(0.0f), kExact));   // nothing on vertex 0
    }
    SUBCASE("cylinder vertex.attribute2: interpolated along the axis of each cylinder") {
        RenderSession s;
        ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "cylinder"));
        // Two indexed cylinders across the view: the upper one (y = 0.5) from vertex 0 at x = -1 (value 0) to
        // vertex 1 at x = +1 (value 1), the lower one (y = -0.5) from vertex 2 at x = +1 (value 0) to vertex 3
        // at x = -1 (value 1). Vertex 4 is unused.
        s.setObject(geometry, "vertex.position", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, 0.5f, 0}, {1, 0.5f, 0}, {1, -0.5f, 0}, {-1, -0.5f, 0}, {0, 5, 0}}));
        s.setObject(geometry, "primitive.index", ANARI_ARRAY1D,
                    s.array(ANARI_UINT32_VEC2, std::vector<glm::uvec2>{{0, 1}, {2, 3}}));
        s.setObject(geometry, "vertex.attribute2", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32, std::vector<float>{0.0f, 1.0f, 0.0f, 1.0f, 7.0f}));
        s.set(geometry, "radius", 0.4f);
        s.commit(geometry);
        const Image image = renderAttribute(s, geometry, "attribute2", {16, 16});
        // Over a pixel x changes by 1/8, the value by 1/16. Rows 12 and 3 cross the cylinders' axes.
        for (uint32_t x = 0; x < 16; ++x) {
            const float along = (float(x) + 0.5f) / 16.0f;
            INFO("pixel " << x << " got " << image.at(x, 12).r << " and " << image.at(x, 3).r);
            CHECK(std::abs(image.at(x, 12).r - along) <= 1.0f / 32.0f + kExact);
            CHECK(std::abs(image.at(x, 3).r - (1.0f - along)) <= 1.0f / 32.0f + kExact);
            CHECK(image.at(x, 12).g == 0.0f);  // a FLOAT32 attribute's missing components: (v, 0, 0, 1)
        }
    }
    SUBCASE("curve vertex.attribute0: piecewise linear over its segments, primitive.attribute1 per segment") {
        RenderSession s;
        ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "curve"));
        s.setObject(geometry, "vertex.position", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}}));
        s.setObject(geometry, "vertex.attribute0", ANARI_ARRAY1D,
                    s.array(ANARI_FLOAT32, std::vector<float>{0.0f, 0.25f, 1.0f}));
        s.setObject(geometry, "primitive.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.set(geometry, "radius", 0.3f);
        s.commit(geometry);
        const Image image = renderAttribute(s, geometry, "attribute0", {16, 16});
        for (uint32_t x = 0; x < 16; ++x) {
            const float px = -1.0f + (float(x) + 0.5f) / 8.0f;
            const float expected = px < 0.0f ? 0.25f * (px + 1.0f) : 0.25f + 0.75f * px;
            INFO("pixel " << x << " got " << image.at(x, 8).r << " expected " << expected);
            CHECK(std::abs(image.at(x, 8).r - expected) <= 0.75f / 16.0f + kExact);
        }
        const Image perSegment = renderAttribute(s, geometry, "attribute1", {16, 16});
        CHECK(near(glm::vec3(perSegment.at(4, 8)), glm::vec3(left), kExact));
        CHECK(near(glm::vec3(perSegment.at(11, 8)), glm::vec3(right), kExact));
    }
    SUBCASE("instance attribute1 and color replace the geometry's") {
        RenderSession s;
        ANARIGeometry geometry = twoSpheres(s);
        s.setObject(geometry, "vertex.attribute1", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.setObject(geometry, "vertex.color", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC4, std::vector{left, right}));
        s.commit(geometry);
        auto placed = [](RenderSession& session, ANARISurface surface) {
            ANARIGroup group = session.keep(anariNewGroup(session.device));
            session.setObject(group, "surface", ANARI_ARRAY1D, session.objects(ANARI_SURFACE, {surface}));
            session.commit(group);
            ANARIInstance instance = session.keep(anariNewInstance(session.device, "transform"));
            session.setObject(instance, "group", ANARI_GROUP, group);
            session.set(instance, "attribute1", glm::vec4(0.3f, 0.0f, 0.8f, 1.0f));
            session.set(instance, "color", glm::vec4(0.0f, 0.6f, 0.1f, 1.0f));
            session.commit(instance);
            return instance;
        };
        for (const char* attribute : {"attribute1", "color"}) {
            CAPTURE(attribute);
            const glm::vec3 expected = std::string(attribute) == "color" ? glm::vec3(0.0f, 0.6f, 0.1f) : glm::vec3(0.3f, 0.0f, 0.8f);
            const Image image = renderAttribute(s, geometry, attribute, {8, 8}, +placed);
            CHECK(near(glm::vec3(image.at(2, 4)), expected, kExact));
            CHECK(near(glm::vec3(image.at(5, 4)), expected, kExact));
            // Without the instance, the geometry's own values.
            const Image plain = renderAttribute(s, geometry, attribute, {8, 8});
            CHECK(near(glm::vec3(plain.at(2, 4)), glm::vec3(left), kExact));
        }
    }
}
