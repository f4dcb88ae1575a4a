// The glTF importer on the shared sample files (exact counts from their README and JSON) and on small files
// the test writes to pin one feature each: instancing, hierarchy, cameras, lights, textures, sparse data.
#include "io/gltf/GltfScene.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cstring>

using ripple::apps::GltfCamera;
using ripple::apps::GltfLight;
using ripple::apps::GltfScene;
using ripple::apps::GltfWrap;
using ripple::apps::loadGltf;
using namespace ripple::test;

namespace {

// A file of the shared scenes, or an empty path (and a message) when the folder is absent.
std::filesystem::path sample(const char* name) {
    const std::filesystem::path file = std::filesystem::path(RIPPLE_DATA_DIR) / "gltf" / name;
    if (!std::filesystem::exists(file)) MESSAGE("skipped: " << file << " is absent (set RIPPLE_DATA_DIR)");
    return std::filesystem::exists(file) ? file : std::filesystem::path();
}

// Floats compared to 1e-5 relative: values computed in double and rounded once.
bool near(const glm::vec3& a, const glm::vec3& b) { return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(1e-5f) * (1.0f + glm::abs(b)))); }

}  // namespace

TEST_CASE("sample files: exact counts") {
    struct Expected {
        const char* file;
        uint64_t stored, drawn;
        size_t materials, textures, cameras, lights, instances;
    };
    const Expected expected[] = {
        {"bunny.glb", 69630, 69630, 1, 0, 0, 0, 1},
        {"cornell-box.glb", 36, 36, 8, 0, 1, 0, 1},
        {"damaged-helmet.glb", 15452, 15452, 1, 5, 0, 0, 1},
        {"metal-rough-spheres.glb", 12209, 1040409, 98, 0, 0, 0, 102},
        {"sponza-lod4-geometry.glb", 187364, 187364, 0, 0, 0, 0, 1},
    };
    for (const Expected& e : expected) {
        CAPTURE(e.file);
        const std::filesystem::path file = sample(e.file);
        if (file.empty()) continue;
        const GltfScene scene = loadGltf(file);
        CHECK(scene.trianglesStored() == e.stored);
        CHECK(scene.trianglesDrawn() == e.drawn);
        CHECK(scene.materials.size() == e.materials);
        CHECK(scene.textures.size() == e.textures);
        CHECK(scene.cameras.size() == e.cameras);
        CHECK(scene.lights.size() == e.lights);
        CHECK(scene.instances.size() == e.instances);
        CHECK(scene.warnings.empty());
        CHECK(scene.boundsMin.x < scene.boundsMax.x);
    }
}

TEST_CASE("sample files: details") {
    SUBCASE("cornell box: camera node and emissive strength") {
        const std::filesystem::path file = sample("cornell-box.glb");
        if (file.empty()) return;
        const GltfScene scene = loadGltf(file);
        REQUIRE(scene.cameras.size() == 1);
        CHECK(near(scene.cameras[0].position, {0.0f, 1.0f, 3.85f}));
        CHECK(near(scene.cameras[0].direction, {0.0f, 0.0f, -1.0f}));
        CHECK(scene.cameras[0].kind == GltfCamera::Kind::Perspective);
        // The "light" material: emissiveFactor (1, 0.70588, 0.23529) x KHR_materials_emissive_strength 17.
        const auto light = std::find_if(scene.materials.begin(), scene.materials.end(), [](auto& m) { return m.name == "light"; });
        REQUIRE(light != scene.materials.end());
        CHECK(near(light->emissive, glm::vec3(1.0f, 0.7058823529f, 0.2352941176f) * 17.0f));
    }
    SUBCASE("damaged helmet: five 2048x2048 images, base colour texture read through TEXCOORD_0") {
        const std::filesystem::path file = sample("damaged-helmet.glb");
        if (file.empty()) return;
        const GltfScene scene = loadGltf(file);
        REQUIRE(scene.images.size() == 5);
        for (const auto& image : scene.images) {
            CHECK(image.width == 2048);
            CHECK(image.height == 2048);
            CHECK(image.rgba.size() == size_t(2048) * 2048 * 4);
        }
        REQUIRE(scene.materials.size() == 1);
        CHECK(scene.materials[0].baseColorTexture == 0);
        CHECK(scene.materials[0].metallicRoughnessTexture == 1);
        REQUIRE(scene.geometries.size() == 1);
        CHECK(scene.geometries[0].texcoords.size() == scene.geometries[0].positions.size());
        CHECK(scene.geometries[0].normals.size() == scene.geometries[0].positions.size());
    }
}

TEST_CASE("instancing: two nodes share one mesh; a mesh per material shares one geometry") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[0,1,2]}])");
    s.replace(R"("nodes":[{"mesh":0}])",
              R"("nodes":[{"mesh":0},{"mesh":0,"translation":[5,0,0]},{"mesh":1,"translation":[0,0,-2]}])");
    s.replace(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])",
              R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]},
                           {"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
                 "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,1]}}])");
    const GltfScene scene = loadGltf(writeGlb(dir / "instances.glb", s));
    CHECK(scene.geometries.size() == 1);
    CHECK(scene.meshes.size() == 2);
    CHECK(scene.instances.size() == 3);
    CHECK(scene.trianglesStored() == 1);
    CHECK(scene.trianglesDrawn() == 3);
    CHECK(scene.meshes[1].primitives[0].material == 0);
    CHECK(near(glm::vec3(scene.materials[0].baseColorFactor), {0.5f, 0.25f, 1.0f}));
    // Bounds of the triangle (0,0,0) (1,0,0) (0,1,0) at x offsets 0 and 5 and z offset -2.
    CHECK(near(scene.boundsMin, {0.0f, 0.0f, -2.0f}));
    CHECK(near(scene.boundsMax, {6.0f, 1.0f, 0.0f}));
}

TEST_CASE("node hierarchy: world transform is parent times child") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("nodes":[{"mesh":0}])",
              R"("nodes":[{"translation":[10,0,0],"children":[1]},{"mesh":0,"scale":[2,2,2],"rotation":[0,0,0.7071067811865476,0.7071067811865476]}])");
    const GltfScene scene = loadGltf(writeGlb(dir / "hierarchy.glb", s));
    REQUIRE(scene.instances.size() == 1);
    CHECK(scene.instances[0].node == 1);
    // Scale 2, then 90 degrees about +Z: (1,0,0) -> (0,2,0), (0,1,0) -> (-2,0,0); then x + 10.
    CHECK(near(scene.boundsMin, {8.0f, 0.0f, 0.0f}));
    CHECK(near(scene.boundsMax, {10.0f, 2.0f, 0.0f}));
}

TEST_CASE("cameras and punctual lights take their node's transform") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[0,1,2,3]}])");
    // Node 1: +90 degrees about +Y, which turns the local -Z view direction into -X.
    s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0},
        {"camera":0,"translation":[1,2,3],"rotation":[0,0.7071067811865476,0,0.7071067811865476]},
        {"camera":1,"extensions":{"KHR_lights_punctual":{"light":0}}},
        {"translation":[0,4,0],"rotation":[-0.7071067811865476,0,0,0.7071067811865476],"extensions":{"KHR_lights_punctual":{"light":1}}}],
      "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}},
                 {"type":"orthographic","orthographic":{"xmag":3,"ymag":2,"znear":0.1,"zfar":50}}],
      "extensionsUsed":["KHR_lights_punctual"],
      "extensions":{"KHR_lights_punctual":{"lights":[
        {"type":"directional","intensity":3,"color":[1,0.5,0.25]},
        {"type":"spot","intensity":40,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.6}}]}})");
    const GltfScene scene = loadGltf(writeGlb(dir / "views.glb", s));
    REQUIRE(scene.cameras.size() == 2);
    CHECK(scene.cameras[0].kind == GltfCamera::Kind::Perspective);
    CHECK(scene.cameras[0].yfov == doctest::Approx(0.5));
    CHECK(scene.cameras[0].aspectRatio == 0.0f);
    CHECK(near(scene.cameras[0].position, {1.0f, 2.0f, 3.0f}));
    CHECK(near(scene.cameras[0].direction, {-1.0f, 0.0f, 0.0f}));
    CHECK(near(scene.cameras[0].up, {0.0f, 1.0f, 0.0f}));
    CHECK(scene.cameras[1].kind == GltfCamera::Kind::Orthographic);
    CHECK(scene.cameras[1].ymag == doctest::Approx(2.0));
    CHECK(scene.cameras[1].zfar == doctest::Approx(50.0));
    REQUIRE(scene.lights.size() == 2);
    CHECK(scene.lights[0].kind == GltfLight::Kind::Directional);
    CHECK(scene.lights[0].intensity == doctest::Approx(3.0));
    CHECK(near(scene.lights[0].color, {1.0f, 0.5f, 0.25f}));
    CHECK(near(scene.lights[0].direction, {0.0f, 0.0f, -1.0f}));
    // Node 3: -90 degrees about +X turns -Z into -Y: a spot at height 4 shining down.
    CHECK(scene.lights[1].kind == GltfLight::Kind::Spot);
    CHECK(near(scene.lights[1].position, {0.0f, 4.0f, 0.0f}));
    CHECK(near(scene.lights[1].direction, {0.0f, -1.0f, 0.0f}));
    CHECK(scene.lights[1].innerConeAngle == doctest::Approx(0.2));
    CHECK(scene.lights[1].outerConeAngle == doctest::Approx(0.6));
}

TEST_CASE("texture in a buffer view: decoded exactly, sampler and factors kept") {
    TempFolder dir;
    GltfSource s = triangleSource();
    const std::vector<uint8_t> texels = {255, 0, 0, 255, 0, 255, 0, 255,     // top row: red, green
                                         0, 0, 255, 255, 255, 255, 255, 128}; // bottom row: blue, half-clear white
    const std::vector<uint8_t> png = pngBytes(2, 2, texels);
    const uint8_t uvs[6] = {0, 0, 255, 0, 0, 255};  // normalized uint8 TEXCOORD_0, padded to 8 bytes below
    s.bin.insert(s.bin.end(), uvs, uvs + 6);
    s.bin.insert(s.bin.end(), {0, 0});
    const size_t pngOffset = s.bin.size();
    s.bin.insert(s.bin.end(), png.begin(), png.end());
    s.replace(R"("buffers":[{"byteLength":48}])", R"("buffers":[{"byteLength":)" + std::to_string(s.bin.size()) + "}]");
    s.replace(R"({"buffer":0,"byteOffset":36,"byteLength":12}])",
              R"({"buffer":0,"byteOffset":36,"byteLength":12},{"buffer":0,"byteOffset":48,"byteLength":6},
                 {"buffer":0,"byteOffset":)" + std::to_string(pngOffset) + R"(,"byteLength":)" + std::to_string(png.size()) + "}]");
    s.replace(R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}])",
              R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"},
                 {"bufferView":2,"componentType":5121,"normalized":true,"count":3,"type":"VEC2"}],
                 "images":[{"bufferView":3,"mimeType":"image/png"}],
                 "samplers":[{"magFilter":9728,"wrapS":33071,"wrapT":33648}],
                 "textures":[{"sampler":0,"source":0}],
                 "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"baseColorFactor":[1,0.5,0.25,1],
                               "metallicFactor":0.25,"roughnessFactor":0.75},"alphaMode":"MASK","alphaCutoff":0.3,"doubleSided":true}])");
    s.replace(R"({"POSITION":0},"indices":1})", R"({"POSITION":0,"TEXCOORD_0":2},"indices":1,"material":0})");

    const GltfScene scene = loadGltf(writeGlb(dir / "texture.glb", s));
    REQUIRE(scene.images.size() == 1);
    CHECK(scene.images[0].width == 2);
    CHECK(scene.images[0].height == 2);
    CHECK(scene.images[0].rgba == texels);  // PNG is lossless: exact
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].wrapS == GltfWrap::ClampToEdge);
    CHECK(scene.textures[0].wrapT == GltfWrap::MirroredRepeat);
    CHECK_FALSE(scene.textures[0].linearFilter);
    const auto& m = scene.materials.at(0);
    CHECK(m.baseColorTexture == 0);
    CHECK(m.metallic == doctest::Approx(0.25));
    CHECK(m.roughness == doctest::Approx(0.75));
    CHECK(m.alphaMode == ripple::apps::GltfAlphaMode::Mask);
    CHECK(m.alphaCutoff == doctest::Approx(0.3));
    CHECK(m.doubleSided);
    const auto& uv = scene.geometries.at(0).texcoords;
    REQUIRE(uv.size() == 3);
    CHECK(uv[1] == glm::vec2(1.0f, 0.0f));  // 255 normalizes to exactly 1
    CHECK(uv[2] == glm::vec2(0.0f, 1.0f));

    SUBCASE("not decoded when the reader asks for geometry only") {
        const GltfScene geometryOnly = loadGltf(dir / "texture.glb", {.decodeImages = false});
        CHECK(geometryOnly.images.at(0).rgba.empty());
        CHECK(geometryOnly.trianglesStored() == 1);
    }
}

TEST_CASE("sparse accessor, RGB vertex colours, skipped modes, files without a scene") {
    TempFolder dir;
    GltfSource s = triangleSource();
    // Sparse: element 2 of POSITION replaced by (0,0,5), index (uint8) and value stored after the indices.
    const uint8_t sparseIndex[4] = {2, 0, 0, 0};
    s.bin.insert(s.bin.end(), sparseIndex, sparseIndex + 4);
    const float value[3] = {0, 0, 5};
    const size_t valueOffset = s.bin.size();
    s.bin.resize(s.bin.size() + 12);
    std::memcpy(s.bin.data() + valueOffset, value, 12);
    // COLOR_0 as float VEC3 reusing the position bytes: alpha must read 1.
    s.replace(R"("buffers":[{"byteLength":48}])", R"("buffers":[{"byteLength":64}])");
    s.replace(R"({"buffer":0,"byteOffset":36,"byteLength":12}])",
              R"({"buffer":0,"byteOffset":36,"byteLength":12},{"buffer":0,"byteOffset":48,"byteLength":16}])");
    s.replace(R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})",
              R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                  "sparse":{"count":1,"indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":2,"byteOffset":4}}})");
    s.replace(R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}])",
              R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"},
                 {"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}])");
    s.replace(R"("primitives":[{"attributes":{"POSITION":0},"indices":1}])",
              R"("primitives":[{"attributes":{"POSITION":0,"COLOR_0":2},"indices":1},{"attributes":{"POSITION":0},"mode":1}])");
    s.replace(R"("scene":0,"scenes":[{"nodes":[0]}],)", "");

    const GltfScene scene = loadGltf(writeGlb(dir / "sparse.glb", s));
    REQUIRE(scene.geometries.size() == 1);
    const auto& g = scene.geometries[0];
    CHECK(g.positions[2] == glm::vec3(0.0f, 0.0f, 5.0f));
    CHECK(g.positions[1] == glm::vec3(1.0f, 0.0f, 0.0f));
    REQUIRE(g.colors.size() == 3);
    CHECK(g.colors[1] == glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    CHECK(scene.instances.size() == 1);  // no scene: every root node
    REQUIRE(scene.warnings.size() == 1);
    CHECK(scene.warnings[0] == "mesh 0 primitive 1: mode 1 is not TRIANGLES; skipped");
}
