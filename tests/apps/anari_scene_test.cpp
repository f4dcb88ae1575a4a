// What the scene builders hand an ANARI device, recorded by the fake API (FakeAnari.h): only object types,
// parameter names, types, element types and string values that the KHR specification defines (table below,
// transcribed from the ANARI 1.0 object definitions), every object committed, every handle but the world
// released, and exact object counts for the sample files and the demo scenes.
#include "apps/scene/AnariScene.h"
#include "apps/scene/DemoScene.h"
#include "tests/apps/FakeAnari.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>

#include <set>
#include <sstream>

using namespace ripple::apps;
using namespace ripple::test;

namespace {

struct Allowed {
    std::set<ANARIDataType> types;
    std::set<ANARIDataType> elements = {};   // arrays: allowed element types
    std::set<std::string> values = {};       // strings: allowed values (empty: any)
};
using ParameterTable = std::map<std::string, Allowed>;

const std::set<ANARIDataType> kFloatVecs = {ANARI_FLOAT32, ANARI_FLOAT32_VEC2, ANARI_FLOAT32_VEC3, ANARI_FLOAT32_VEC4};
const std::set<ANARIDataType> kColorParam = {ANARI_FLOAT32_VEC3, ANARI_SAMPLER, ANARI_STRING};
const std::set<ANARIDataType> kFloatParam = {ANARI_FLOAT32, ANARI_SAMPLER, ANARI_STRING};
const Allowed kVec3 = {{ANARI_FLOAT32_VEC3}};
const Allowed kFloat = {{ANARI_FLOAT32}};

// Object "type/subtype" -> parameters, from the KHR_* definitions of the parameters the builders may use.
const std::map<std::string, ParameterTable>& specification() {
    static const std::map<std::string, ParameterTable> table = {
        {"geometry/triangle",
         {{"vertex.position", {{ANARI_ARRAY1D}, {ANARI_FLOAT32_VEC3}}},
          {"vertex.normal", {{ANARI_ARRAY1D}, {ANARI_FLOAT32_VEC3}}},
          {"vertex.attribute0", {{ANARI_ARRAY1D}, kFloatVecs}},
          {"vertex.color", {{ANARI_ARRAY1D}, kFloatVecs}},
          {"primitive.color", {{ANARI_ARRAY1D}, kFloatVecs}},
          {"primitive.index", {{ANARI_ARRAY1D}, {ANARI_UINT32_VEC3}}}}},
        {"geometry/isosurface", {{"field", {{ANARI_SPATIAL_FIELD}}}, {"isovalue", {{ANARI_FLOAT32, ANARI_ARRAY1D}, {ANARI_FLOAT32}}}}},
        {"geometry/sphere", {{"vertex.position", {{ANARI_ARRAY1D}, {ANARI_FLOAT32_VEC3}}}, {"radius", kFloat}}},
        {"geometry/cylinder",
         {{"vertex.position", {{ANARI_ARRAY1D}, {ANARI_FLOAT32_VEC3}}},
          {"radius", kFloat},
          {"caps", {{ANARI_STRING}, {}, {"none", "first", "second", "both"}}}}},
        {"material/matte", {{"color", {kColorParam}}}},
        {"material/physicallyBased",
         {{"baseColor", {kColorParam}},
          {"opacity", {kFloatParam}},
          {"metallic", {kFloatParam}},
          {"roughness", {kFloatParam}},
          {"emissive", {kColorParam}},
          {"normal", {{ANARI_SAMPLER}}},
          {"alphaMode", {{ANARI_STRING}, {}, {"opaque", "blend", "mask"}}},
          {"alphaCutoff", kFloat}}},
        {"sampler/image2D",
         {{"image", {{ANARI_ARRAY2D}, {ANARI_UFIXED8_VEC4, ANARI_UFIXED8_RGBA_SRGB}}},
          {"inAttribute", {{ANARI_STRING}, {}, {"attribute0"}}},
          {"filter", {{ANARI_STRING}, {}, {"nearest", "linear"}}},
          {"wrapMode1", {{ANARI_STRING}, {}, {"clampToEdge", "repeat", "mirrorRepeat"}}},
          {"wrapMode2", {{ANARI_STRING}, {}, {"clampToEdge", "repeat", "mirrorRepeat"}}},
          {"outTransform", {{ANARI_FLOAT32_MAT4}}}}},
        {"surface/", {{"geometry", {{ANARI_GEOMETRY}}}, {"material", {{ANARI_MATERIAL}}}}},
        {"spatial_field/structuredRegular",
         {{"data", {{ANARI_ARRAY3D}, {ANARI_UFIXED8, ANARI_FIXED16, ANARI_UFIXED16, ANARI_FLOAT32, ANARI_FLOAT64}}},
          {"origin", kVec3},
          {"spacing", kVec3}}},
        {"volume/transferFunction1D",
         {{"value", {{ANARI_SPATIAL_FIELD}}},
          {"valueRange", {{ANARI_FLOAT32_BOX1, ANARI_FLOAT64_BOX1}}},
          {"color", {{ANARI_FLOAT32_VEC3, ANARI_FLOAT32_VEC4, ANARI_ARRAY1D}, {ANARI_FLOAT32_VEC3, ANARI_FLOAT32_VEC4}}},
          {"opacity", {{ANARI_FLOAT32, ANARI_ARRAY1D}, {ANARI_FLOAT32}}},
          {"unitDistance", kFloat}}},
        {"group/", {{"surface", {{ANARI_ARRAY1D}, {ANARI_SURFACE}}}, {"volume", {{ANARI_ARRAY1D}, {ANARI_VOLUME}}}}},
        {"instance/transform", {{"transform", {{ANARI_FLOAT32_MAT4}}}, {"group", {{ANARI_GROUP}}}}},
        {"world/", {{"instance", {{ANARI_ARRAY1D}, {ANARI_INSTANCE}}}, {"light", {{ANARI_ARRAY1D}, {ANARI_LIGHT}}}}},
        {"light/directional", {{"color", kVec3}, {"direction", kVec3}, {"irradiance", kFloat}, {"angularDiameter", kFloat}}},
        {"light/point", {{"color", kVec3}, {"position", kVec3}, {"intensity", kFloat}}},
        {"light/spot",
         {{"color", kVec3}, {"position", kVec3}, {"direction", kVec3}, {"intensity", kFloat}, {"openingAngle", kFloat},
          {"falloffAngle", kFloat}}},
        {"light/quad",
         {{"color", kVec3}, {"position", kVec3}, {"edge1", kVec3}, {"edge2", kVec3}, {"radiance", kFloat},
          {"side", {{ANARI_STRING}, {}, {"front", "back", "both"}}}}},
        {"camera/perspective",
         {{"position", kVec3}, {"direction", kVec3}, {"up", kVec3}, {"aspect", kFloat}, {"fovy", kFloat}}},
        {"camera/orthographic",
         {{"position", kVec3}, {"direction", kVec3}, {"up", kVec3}, {"aspect", kFloat}, {"height", kFloat}}},
    };
    return table;
}

std::string typeName(ANARIDataType type) {
    switch (type) {
        case ANARI_GEOMETRY: return "geometry";
        case ANARI_MATERIAL: return "material";
        case ANARI_SAMPLER: return "sampler";
        case ANARI_SURFACE: return "surface";
        case ANARI_GROUP: return "group";
        case ANARI_INSTANCE: return "instance";
        case ANARI_WORLD: return "world";
        case ANARI_LIGHT: return "light";
        case ANARI_CAMERA: return "camera";
        case ANARI_SPATIAL_FIELD: return "spatial_field";
        case ANARI_VOLUME: return "volume";
        default: return "type " + std::to_string(type);
    }
}

// Every way the recorded calls depart from the specification or from ANARI's object lifetime rules, one
// line each; empty when all is well. `kept` is the one handle the caller still owns (the world).
std::string violations(const FakeDevice& device, ANARIObject kept) {
    std::ostringstream out;
    for (const std::string& m : device.misuse) out << "misuse: " << m << "\n";
    for (const auto& o : device.objects) {
        const int expectedReferences = o.get() == fakeObject(kept) ? 1 : 0;
        if (o->appReferences != expectedReferences)
            out << typeName(o->type) << "/" << o->subtype << ": " << o->appReferences << " app references left\n";
        if (o->type == ANARI_ARRAY1D || o->type == ANARI_ARRAY2D || o->type == ANARI_ARRAY3D) continue;
        const std::string key = typeName(o->type) + "/" + o->subtype;
        const auto table = specification().find(key);
        if (table == specification().end()) {
            out << key << ": not an object the specification table allows\n";
            continue;
        }
        if (!o->committed) out << key << ": never committed\n";
        for (const auto& [name, p] : o->parameters) {
            const auto allowed = table->second.find(name);
            if (allowed == table->second.end()) {
                out << key << ": parameter '" << name << "' is not in the specification\n";
                continue;
            }
            if (!allowed->second.types.count(p.type)) out << key << "." << name << ": type " << p.type << " not allowed\n";
            if (p.object && !allowed->second.elements.empty() && !allowed->second.elements.count(p.object->elementType))
                out << key << "." << name << ": element type " << p.object->elementType << " not allowed\n";
            if (p.type == ANARI_STRING && !allowed->second.values.empty() && !allowed->second.values.count(p.text))
                out << key << "." << name << ": value '" << p.text << "' not allowed\n";
        }
    }
    return out.str();
}

size_t count(ANARIDataType type, const std::string& subtype = "*") { return fakeDevice().ofType(type, subtype).size(); }

std::filesystem::path sample(const char* name) {
    const std::filesystem::path file = std::filesystem::path(RIPPLE_DATA_DIR) / "gltf" / name;
    if (!std::filesystem::exists(file)) MESSAGE("skipped: " << file << " is absent (set RIPPLE_DATA_DIR)");
    return std::filesystem::exists(file) ? file : std::filesystem::path();
}

}  // namespace

TEST_CASE("glTF sample files become spec-conforming ANARI objects, shared as the file shares them") {
    SUBCASE("metal-rough-spheres: 26 geometries, 102 groups and instances") {
        const auto file = sample("metal-rough-spheres.glb");
        if (file.empty()) return;
        const GltfScene scene = loadGltf(file);
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildAnariWorld(d, scene);
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_GEOMETRY, "triangle") == 26);
        CHECK(count(ANARI_MATERIAL, "physicallyBased") == 99);  // 98 + glTF's default for 25 primitives without one
        CHECK(count(ANARI_GROUP) == 102);
        CHECK(count(ANARI_INSTANCE, "transform") == 102);
        CHECK(count(ANARI_SURFACE) == 123);  // one per distinct (geometry, material) pair of the 123 primitives
        CHECK(count(ANARI_SAMPLER) == 0);
        CHECK(count(ANARI_LIGHT, "directional") == 1);  // no lights, no emission: the studio key light
        CHECK(world.ambientRadiance > 0.0f);
        // Stored triangles: the primitive.index arrays hold 12,209 triangles in all.
        uint64_t triangles = 0;
        for (const FakeObject* g : fakeDevice().ofType(ANARI_GEOMETRY))
            triangles += g->parameters.at("primitive.index").object->count1;
        CHECK(triangles == 12209);
    }
    SUBCASE("cornell box: emissive light material, its camera, no added light") {
        const auto file = sample("cornell-box.glb");
        if (file.empty()) return;
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildAnariWorld(d, loadGltf(file));
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_GEOMETRY, "triangle") == 8);
        CHECK(count(ANARI_LIGHT) == 0);
        CHECK(world.ambientRadiance == 0.0f);
        int emissive = 0;
        for (const FakeObject* m : fakeDevice().ofType(ANARI_MATERIAL))
            if (m->parameters.count("emissive")) {
                ++emissive;
                const glm::vec3 e = m->parameters.at("emissive").as<glm::vec3>();
                CHECK(e.x == doctest::Approx(17.0));
                CHECK(e.y == doctest::Approx(0.7058823529 * 17.0));
                CHECK(e.z == doctest::Approx(0.2352941176 * 17.0));
            }
        CHECK(emissive == 1);
        REQUIRE(world.cameras.size() == 1);
        CHECK(world.cameras[0].position.z == doctest::Approx(3.85));
    }
    SUBCASE("damaged helmet: samplers over sRGB and linear images, texcoords in attribute0") {
        const auto file = sample("damaged-helmet.glb");
        if (file.empty()) return;
        const GltfScene scene = loadGltf(file);
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildAnariWorld(d, scene);
        CHECK(violations(fakeDevice(), world.world) == "");
        // baseColor, metallic, roughness, emissive, normal
        CHECK(count(ANARI_SAMPLER, "image2D") == 5);
        // baseColor and emissive images as sRGB, the metallic-roughness and normal images as linear data
        const auto images = fakeDevice().ofType(ANARI_ARRAY2D);
        REQUIRE(images.size() == 4);
        int srgb = 0;
        for (const FakeObject* a : images) {
            CHECK(a->count1 == 2048);
            CHECK(a->count2 == 2048);
            srgb += a->elementType == ANARI_UFIXED8_RGBA_SRGB;
        }
        CHECK(srgb == 2);
        const FakeObject* geometry = fakeDevice().ofType(ANARI_GEOMETRY).at(0);
        const FakeObject* uv = geometry->parameters.at("vertex.attribute0").object;
        CHECK(uv->elementType == ANARI_FLOAT32_VEC2);
        CHECK(uv->count1 == scene.geometries.at(0).texcoords.size());
        // Emission only through a texture does not light a scene: the key light is added.
        CHECK(count(ANARI_LIGHT, "directional") == 1);
    }
}

TEST_CASE("glTF to ANARI: instances, vertex colours and punctual lights") {
    TempFolder dir;
    GltfSource s = triangleSource();
    s.replace(R"("scenes":[{"nodes":[0]}])", R"("scenes":[{"nodes":[0,1,2]}])");
    s.replace(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0},{"mesh":0,"translation":[5,0,0]},
        {"translation":[0,4,0],"rotation":[-0.7071067811865476,0,0,0.7071067811865476],"extensions":{"KHR_lights_punctual":{"light":0}}}],
      "extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","intensity":40,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.6}}]}})");
    // COLOR_0 reads the position bytes as float RGB: vertex 1 is (1, 0, 0).
    s.replace(R"({"POSITION":0})", R"({"POSITION":0,"COLOR_0":2})");
    s.replace(R"("type":"SCALAR"}])", R"("type":"SCALAR"},{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}])");
    ANARIDevice d = newFakeDevice();
    const AnariWorld world = buildAnariWorld(d, loadGltf(writeGlb(dir / "lit.glb", s)));
    CHECK(violations(fakeDevice(), world.world) == "");
    CHECK(count(ANARI_GEOMETRY) == 1);
    CHECK(count(ANARI_GROUP) == 1);
    const auto instances = fakeDevice().ofType(ANARI_INSTANCE);
    REQUIRE(instances.size() == 2);
    CHECK(instances[1]->parameters.at("transform").as<glm::mat4>()[3] == glm::vec4(5.0f, 0.0f, 0.0f, 1.0f));
    CHECK(instances[0]->parameters.at("group").object == instances[1]->parameters.at("group").object);

    const FakeObject* material = fakeDevice().ofType(ANARI_MATERIAL).at(0);
    CHECK(material->parameters.at("baseColor").text == "color");
    const FakeObject* colors = fakeDevice().ofType(ANARI_GEOMETRY).at(0)->parameters.at("vertex.color").object;
    REQUIRE(colors->elementType == ANARI_FLOAT32_VEC4);
    CHECK(colors->elements<glm::vec4>()[1] == glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));

    // glTF half angles (0.2 inner, 0.6 outer) -> ANARI full opening 1.2 and falloff ring 0.4.
    const auto spots = fakeDevice().ofType(ANARI_LIGHT, "spot");
    REQUIRE(spots.size() == 1);
    CHECK(spots[0]->parameters.at("openingAngle").as<float>() == doctest::Approx(1.2));
    CHECK(spots[0]->parameters.at("falloffAngle").as<float>() == doctest::Approx(0.4));
    CHECK(spots[0]->parameters.at("intensity").as<float>() == doctest::Approx(40.0));
    const glm::vec3 direction = spots[0]->parameters.at("direction").as<glm::vec3>();
    CHECK(direction.y == doctest::Approx(-1.0));
    CHECK(count(ANARI_LIGHT) == 1);  // the file's own light: nothing added
}

TEST_CASE("demo scenes are spec-conforming and complete") {
    SUBCASE("default") {
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildDemoScene(d, "default");
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_GEOMETRY, "sphere") == 8);
        CHECK(count(ANARI_GEOMETRY, "cylinder") == 1);
        CHECK(count(ANARI_GEOMETRY, "triangle") == 2);  // tiled floor, torus
        CHECK(count(ANARI_LIGHT, "directional") == 1);
        CHECK(count(ANARI_LIGHT, "quad") == 1);
        CHECK(world.cameras.size() == 1);
    }
    SUBCASE("cornell") {
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildDemoScene(d, "cornell");
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_GEOMETRY, "triangle") == 4);
        uint64_t triangles = 0;
        for (const FakeObject* g : fakeDevice().ofType(ANARI_GEOMETRY))
            triangles += g->parameters.at("primitive.index").object->count1;
        CHECK(triangles == 10 + 24);  // five walls, two boxes
        CHECK(count(ANARI_LIGHT, "quad") == 1);
    }
    SUBCASE("volume") {
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildDemoScene(d, "volume");
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_SPATIAL_FIELD, "structuredRegular") == 1);
        CHECK(count(ANARI_VOLUME, "transferFunction1D") == 1);
        CHECK(count(ANARI_GEOMETRY, "triangle") == 1);  // the floor
        CHECK(count(ANARI_LIGHT, "directional") == 1);
    }
    SUBCASE("isosurface") {
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildDemoScene(d, "isosurface");
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_SPATIAL_FIELD, "structuredRegular") == 1);
        CHECK(count(ANARI_GEOMETRY, "isosurface") == 1);
        CHECK(count(ANARI_VOLUME, "transferFunction1D") == 0);
        CHECK(count(ANARI_GEOMETRY, "triangle") == 1);  // the floor
    }
    SUBCASE("unknown name") {
        CHECK_THROWS_WITH_AS(buildDemoScene(newFakeDevice(), "teapot"),
                             "unknown demo scene 'teapot' (known: default, cornell, volume, isosurface)",
                             std::invalid_argument);
    }
}

// A field from a file: its box scaled so that the longest side is 2 (5x3x2 samples of spacing 1,2,1: extents
// 4, 4, 1 -> 2, 2, 0.5), centred over the origin just above the floor; the transfer function over the
// data's min..max; one isosurface per isovalue; with isovalues the volume only when a map is named.
TEST_CASE("buildFieldScene places a file's field and draws what the options ask") {
    VolumeData data;
    data.dims = glm::uvec3(5, 3, 2);
    data.spacing = glm::vec3(1.0f, 2.0f, 1.0f);
    data.values.resize(30);
    for (size_t i = 0; i < 30; ++i) data.values[i] = 10.0f + float(i);
    data.minValue = 10.0f;
    data.maxValue = 39.0f;
    FieldSceneOptions options;
    options.opacity = 0.75f;
    SUBCASE("volume") {
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildFieldScene(d, data, options);
        CHECK(violations(fakeDevice(), world.world) == "");
        const auto fields = fakeDevice().ofType(ANARI_SPATIAL_FIELD, "structuredRegular");
        REQUIRE(fields.size() == 1);
        CHECK(fields[0]->parameters.at("origin").as<glm::vec3>() == glm::vec3(-1.0f, 0.05f, -0.25f));
        CHECK(fields[0]->parameters.at("spacing").as<glm::vec3>() == glm::vec3(0.5f, 1.0f, 0.5f));
        const auto volumes = fakeDevice().ofType(ANARI_VOLUME, "transferFunction1D");
        REQUIRE(volumes.size() == 1);
        const auto range = volumes[0]->parameters.at("valueRange").as<glm::vec2>();
        CHECK(range == glm::vec2(10.0f, 39.0f));
        CHECK(volumes[0]->parameters.at("unitDistance").as<float>() == kDefaultUnitDistance);
        const FakeObject* opacity = volumes[0]->parameters.at("opacity").object;
        REQUIRE(opacity->count1 == 2);
        CHECK(opacity->elements<float>()[1] == 0.75f);
        CHECK(count(ANARI_GEOMETRY, "isosurface") == 0);
        CHECK(world.cameras.size() == 1);
    }
    SUBCASE("isosurfaces alone") {
        options.transferFunction = "";
        options.isovalues = {12.0f, 20.0f, 30.0f};
        ANARIDevice d = newFakeDevice();
        const AnariWorld world = buildFieldScene(d, data, options);
        CHECK(violations(fakeDevice(), world.world) == "");
        CHECK(count(ANARI_GEOMETRY, "isosurface") == 3);
        CHECK(count(ANARI_VOLUME, "transferFunction1D") == 0);
    }
    SUBCASE("unknown colour map") {
        options.transferFunction = "jet";
        CHECK_THROWS_WITH_AS(buildFieldScene(newFakeDevice(), data, options),
                             "unknown transfer function 'jet' (known: viridis, coolwarm, grayscale)",
                             std::invalid_argument);
    }
}

TEST_CASE("camera helpers") {
    SUBCASE("framing fits the bounding sphere inside the narrower field of view") {
        for (float aspect : {0.5f, 1.0f, 2.0f}) {
            CAPTURE(aspect);
            const glm::vec3 lo(-1.0f, 2.0f, -3.0f), hi(3.0f, 4.0f, 1.0f);
            const CameraView view = frameBounds(lo, hi, aspect);
            const glm::vec3 center = 0.5f * (lo + hi);
            const float radius = 0.5f * glm::length(hi - lo);
            const float distance = glm::length(center - view.position);
            CHECK(glm::dot(glm::normalize(center - view.position), view.direction) == doctest::Approx(1.0));
            // The sphere's angular radius must not exceed either half field of view.
            const float angular = std::asin(radius / distance);
            const float halfX = std::atan(std::tan(0.5f * view.fovy) * aspect);
            CHECK(angular <= 0.5f * view.fovy + 1e-6f);
            CHECK(angular <= halfX + 1e-6f);
            CHECK(angular >= 0.9f * std::min(0.5f * view.fovy, halfX));  // and does not leave it tiny
        }
    }
    SUBCASE("glTF orthographic camera: ANARI height is twice ymag") {
        GltfCamera c;
        c.kind = GltfCamera::Kind::Orthographic;
        c.ymag = 2.5f;
        const CameraView view = cameraView(c);
        CHECK(view.orthographic);
        CHECK(view.height == 5.0f);
        ANARIDevice d = newFakeDevice();
        ANARICamera camera = newAnariCamera(d, view, 1.5f);
        const FakeObject* recorded = fakeObject(camera);
        CHECK(recorded->subtype == "orthographic");
        CHECK(recorded->parameters.at("height").as<float>() == 5.0f);
        CHECK(recorded->parameters.at("aspect").as<float>() == 1.5f);
        CHECK(violations(fakeDevice(), camera) == "");
    }
}
