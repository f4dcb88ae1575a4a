// Robustness group "bad data": NaN/Inf in every kind of input array and float parameter, indices out of
// range and arrays of the wrong element type. Each case puts one bad object beside a good sphere and checks
// that the device refused it at commit with one error naming the object, the parameter and what is wrong
// where, and that the frame is the frame without the bad object.
#include "apps/ripple-robustness/Robustness.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace ripple::robustness {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Renders are deterministic (same scene, same bits), so a skipped object leaves the frame identical: 1e-5
// allows no visible change. A rendered bad object or its shadow moves pixels by more than 0.01 (the control
// row shows the comparison sees it).
constexpr float kSameImage = 1e-5f;
constexpr float kVisible = 0.01f;

// What a case adds to the scene of the good sphere.
struct Additions {
    std::vector<ANARISurface> surfaces;
    std::vector<ANARIInstance> instances;
    std::vector<ANARILight> lights;
};

// One bad input: what builds it, the fragments its one error must all contain, and what the frame must
// equal: the good scene plus the reference named by referenceKey ("": nothing, the bad object is dropped).
struct BadCase {
    std::string name;
    std::vector<std::string> fragments;
    std::function<Additions(Harness&)> build;
    std::string referenceKey;  // "" or a key of the references below
    bool quick = false;        // part of the tests' sweep
};

const char* kindOf(float bad) {
    return std::isnan(bad) ? "NaN" : bad > 0.0f ? "+Inf" : "-Inf";
}

void setArray(Harness& h, ANARIObject object, const char* name, ANARIArray array) {
    anariSetParameter(h.device(), object, name, ANARI_ARRAY1D, &array);
}

template <class T>
void setValue(Harness& h, ANARIObject object, const char* name, ANARIDataType type, const T& value) {
    anariSetParameter(h.device(), object, name, type, &value);
}

// The right half of the frame holds the bad object: a two-triangle quad, four spheres, or segments.
const std::vector<glm::vec3> kQuadCorners = {
    {0.4f, -0.6f, 0.0f}, {1.6f, -0.6f, 0.0f}, {1.6f, 0.6f, 0.0f}, {0.4f, 0.6f, 0.0f}};
const std::vector<glm::vec3> kPoints = {
    {1.0f, 0.0f, 0.0f}, {1.4f, 0.4f, 0.2f}, {0.7f, -0.3f, 0.3f}, {1.3f, -0.4f, -0.3f}};

// Elements 1 and 2 get `bad` (in component 1 and 0): the error must name element 1 and count 2.
template <class T>
std::vector<T> spoilt(std::vector<T> values, float bad) {
    for (size_t i = 1; i < std::min<size_t>(values.size(), 3); ++i) {
        if constexpr (std::is_same_v<T, float>)
            values[i] = bad;
        else
            values[i][2 - i] = bad;
    }
    return values;
}
// "element 1 holds NaN; 2 of 4": where and how many, as the error must say it.
std::string whereSpoilt(size_t count, float bad, const char* element = "element") {
    const size_t spoiltCount = std::min<size_t>(count, 3) - 1;
    return std::string(element) + " 1 holds " + kindOf(bad) + "; " + std::to_string(spoiltCount) + " of " +
           std::to_string(count);
}

// A surface of `subtype` with the given arrays and floats, matte red-brown.
ANARISurface geometrySurface(Harness& h, const char* subtype,
                             const std::vector<std::pair<const char*, ANARIArray1D>>& arrays,
                             const std::vector<std::pair<const char*, float>>& floats = {},
                             ANARIMaterial material = nullptr) {
    ANARIGeometry geometry = h.keep(anariNewGeometry(h.device(), subtype));
    for (const auto& [name, array] : arrays) setArray(h, geometry, name, array);
    for (const auto& [name, value] : floats) setValue(h, geometry, name, ANARI_FLOAT32, value);
    anariCommitParameters(h.device(), geometry);
    return h.surface(geometry, material ? material : h.matte({0.8f, 0.3f, 0.2f}));
}

ANARIArray1D quadIndex(Harness& h) {
    return h.array(ANARI_UINT32_VEC3, std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}});
}

// A triangle quad with one per-vertex or per-primitive float array spoilt.
template <class T>
BadCase meshArrayCase(const char* parameter, ANARIDataType type, std::vector<T> good, float bad, bool quick) {
    const std::vector<T> values = spoilt(good, bad);
    const std::string where = whereSpoilt(values.size(), bad);
    return {std::string("triangle '") + parameter + "' " + kindOf(bad),
            {"geometry 'triangle'", std::string("'") + parameter + "'", where},
            [=](Harness& h) {
                std::vector<std::pair<const char*, ANARIArray1D>> arrays = {{"primitive.index", quadIndex(h)}};
                if (std::string(parameter) != "vertex.position")
                    arrays.push_back({"vertex.position", h.array(ANARI_FLOAT32_VEC3, kQuadCorners)});
                arrays.push_back({parameter, h.array(type, values)});
                return Additions{{geometrySurface(h, "triangle", arrays)}, {}, {}};
            },
            "",
            quick};
}

// Spheres, cylinders, cones and curves on kPoints with one array spoilt.
BadCase pointArrayCase(const char* subtype, const char* parameter, float bad, bool quick) {
    const bool positions = std::string(parameter) == "vertex.position";
    const bool perPrimitive = std::string(parameter) == "primitive.radius";
    const std::vector<glm::vec3> centres = positions ? spoilt(kPoints, bad) : kPoints;
    const std::vector<float> radii = spoilt(std::vector<float>(perPrimitive ? 2 : 4, 0.2f), bad);
    const std::string where = whereSpoilt(positions ? centres.size() : radii.size(), bad);
    return {std::string(subtype) + " '" + parameter + "' " + kindOf(bad),
            {std::string("geometry '") + subtype + "'", std::string("'") + parameter + "'", where},
            [=](Harness& h) {
                std::vector<std::pair<const char*, ANARIArray1D>> arrays = {
                    {"vertex.position", h.array(ANARI_FLOAT32_VEC3, centres)}};
                const bool needsRadii = std::string(subtype) == "cone" || !positions;
                if (needsRadii)
                    arrays.push_back({positions ? "vertex.radius" : parameter, h.array(ANARI_FLOAT32, radii)});
                return Additions{{geometrySurface(h, subtype, arrays, {{"radius", 0.2f}})}, {}, {}};
            },
            "",
            quick};
}

// A light of `subtype` with one float or vec3 parameter bad; the good light stays.
BadCase lightCase(const char* subtype, const char* parameter, int components, float bad, bool quick) {
    return {std::string("light '") + subtype + "' '" + parameter + "' " + kindOf(bad),
            {std::string("light '") + subtype + "'", std::string("'") + parameter + "'",
             std::string("holds ") + kindOf(bad)},
            [=](Harness& h) {
                ANARILight light = h.keep(anariNewLight(h.device(), subtype));
                if (std::string(subtype) == "hdri") {
                    ANARIArray2D radiance =
                        h.keep(anariNewArray2D(h.device(), nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC3, 4, 2));
                    auto* texels = static_cast<glm::vec3*>(anariMapArray(h.device(), radiance));
                    std::fill(texels, texels + 8, glm::vec3(0.5f));
                    anariUnmapArray(h.device(), radiance);
                    anariSetParameter(h.device(), light, "radiance", ANARI_ARRAY2D, &radiance);
                }
                if (components == 1)
                    setValue(h, light, parameter, ANARI_FLOAT32, bad);
                else
                    setValue(h, light, parameter, ANARI_FLOAT32_VEC3, glm::vec3(0.3f, bad, -1.0f));
                anariCommitParameters(h.device(), light);
                return Additions{{}, {}, {light}};
            },
            "",
            quick};
}

// An hdri light whose radiance texels 1 and 2 are bad.
BadCase hdriTexelCase(float bad, bool quick) {
    const std::vector<glm::vec3> texels = spoilt(std::vector<glm::vec3>(8, glm::vec3(0.5f)), bad);
    return {std::string("light 'hdri' 'radiance' texel ") + kindOf(bad),
            {"light 'hdri'", "'radiance'", whereSpoilt(texels.size(), bad, "texel")},
            [=](Harness& h) {
                ANARILight light = h.keep(anariNewLight(h.device(), "hdri"));
                ANARIArray2D radiance =
                    h.keep(anariNewArray2D(h.device(), nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC3, 4, 2));
                std::copy(texels.begin(), texels.end(), static_cast<glm::vec3*>(anariMapArray(h.device(), radiance)));
                anariUnmapArray(h.device(), radiance);
                anariSetParameter(h.device(), light, "radiance", ANARI_ARRAY2D, &radiance);
                anariCommitParameters(h.device(), light);
                return Additions{{}, {}, {light}};
            },
            "",
            quick};
}

// An instance of spheres whose transform has columns 1 and 3 bad.
BadCase instanceCase(float bad, bool quick) {
    glm::mat4 transform(1.0f);
    transform[1][1] = bad;
    transform[3][0] = bad;
    return {std::string("instance 'transform' ") + kindOf(bad),
            {"instance 'transform'", "'transform'", std::string("column 1 holds ") + kindOf(bad) + "; 2 of 4 columns"},
            [=](Harness& h) {
                ANARISurface spheres = geometrySurface(
                    h, "sphere", {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kPoints)}}, {{"radius", 0.2f}});
                return Additions{{}, {h.instance(h.group({spheres}), transform)}, {}};
            },
            "",
            quick};
}

// The spheres coloured by a sampler of `subtype` with `parameter` bad. The sampler is dropped, so the
// reference is the spheres in the colour a sampler would multiply: white.
BadCase samplerCase(const char* subtype, const char* parameter, float bad, bool quick) {
    const bool matrix = std::string(parameter) == "outTransform";
    const char* element = std::string(subtype) == "primitive" ? "entry" : "texel";
    const std::vector<glm::vec4> texels = spoilt(std::vector<glm::vec4>(4, glm::vec4(0.2f, 0.7f, 0.3f, 1.0f)), bad);
    const std::string where =
        matrix ? std::string("column 1 holds ") + kindOf(bad) : whereSpoilt(texels.size(), bad, element);
    return {
        std::string("sampler '") + subtype + "' '" + parameter + "' " + kindOf(bad),
        {std::string("sampler '") + subtype + "'", std::string("'") + parameter + "'", where},
        [=](Harness& h) {
            ANARISampler sampler = h.keep(anariNewSampler(h.device(), subtype));
            const std::vector<glm::vec4> image = matrix ? std::vector<glm::vec4>(4, glm::vec4(0.5f)) : texels;
            if (std::string(subtype) == "image2D") {
                ANARIArray2D array =
                    h.keep(anariNewArray2D(h.device(), nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, 2, 2));
                std::copy(image.begin(), image.end(), static_cast<glm::vec4*>(anariMapArray(h.device(), array)));
                anariUnmapArray(h.device(), array);
                anariSetParameter(h.device(), sampler, "image", ANARI_ARRAY2D, &array);
            } else if (std::string(subtype) == "primitive") {
                setArray(h, sampler, "array", h.array(ANARI_FLOAT32_VEC4, image));
            }
            if (matrix) {
                glm::mat4 transform(1.0f);
                transform[1][0] = bad;
                anariSetParameter(h.device(), sampler, "outTransform", ANARI_FLOAT32_MAT4, glm::value_ptr(transform));
            }
            anariCommitParameters(h.device(), sampler);
            ANARIMaterial material = h.keep(anariNewMaterial(h.device(), "matte"));
            anariSetParameter(h.device(), material, "color", ANARI_SAMPLER, &sampler);
            anariCommitParameters(h.device(), material);
            return Additions{{geometrySurface(h, "sphere", {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kPoints)}},
                                              {{"radius", 0.2f}}, material)},
                             {},
                             {}};
        },
        "white spheres",
        quick};
}

// The spheres in a material of `subtype` whose `parameter` is bad: the material, so the surface, is dropped.
BadCase materialCase(const char* subtype, const char* parameter, int components, float bad, bool quick) {
    return {std::string("material '") + subtype + "' '" + parameter + "' " + kindOf(bad),
            {std::string("material '") + subtype + "'", std::string("'") + parameter + "'",
             std::string("holds ") + kindOf(bad)},
            [=](Harness& h) {
                ANARIMaterial material = h.keep(anariNewMaterial(h.device(), subtype));
                if (components == 1)
                    setValue(h, material, parameter, ANARI_FLOAT32, bad);
                else
                    setValue(h, material, parameter, ANARI_FLOAT32_VEC3, glm::vec3(0.5f, bad, 0.5f));
                anariCommitParameters(h.device(), material);
                return Additions{
                    {geometrySurface(h, "sphere", {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kPoints)}},
                                     {{"radius", 0.2f}}, material)},
                    {},
                    {}};
            },
            "",
            quick};
}

// A geometry whose "primitive.index" points past its vertices (or below zero).
template <class Index>
BadCase indexCase(const char* subtype, ANARIDataType type, std::vector<Index> index, const std::string& where,
                  bool quick) {
    return {std::string(subtype) + " 'primitive.index' " + where,
            {std::string("geometry '") + subtype + "'", "'primitive.index'", where},
            [=](Harness& h) {
                const bool mesh = std::string(subtype) == "triangle" || std::string(subtype) == "quad";
                return Additions{
                    {geometrySurface(h, subtype,
                                     {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, mesh ? kQuadCorners : kPoints)},
                                      {"primitive.index", h.array(type, index)}},
                                     {{"radius", 0.2f}})},
                    {},
                    {}};
            },
            "",
            quick};
}

// An array of an element type the parameter cannot take. FLOAT32_BOX1 (two floats) is not a number type.
BadCase elementTypeCase(const char* subtype, const char* parameter, ANARIDataType type, const char* typeName,
                        bool quick) {
    return {std::string(subtype) + " '" + parameter + "' of " + typeName,
            {std::string("'") + subtype + "'", std::string("'") + parameter + "'",
             std::string("elements of type ANARI_") + typeName},
            [=](Harness& h) {
                // Managed arrays start zeroed: the contents do not matter, the element type is refused.
                if (std::string(subtype) == "hdri" || std::string(subtype) == "image2D") {
                    ANARIArray2D array = h.keep(anariNewArray2D(h.device(), nullptr, nullptr, nullptr, type, 2, 2));
                    const bool light = std::string(subtype) == "hdri";
                    ANARIObject object = light ? ANARIObject(h.keep(anariNewLight(h.device(), "hdri")))
                                               : ANARIObject(h.keep(anariNewSampler(h.device(), "image2D")));
                    anariSetParameter(h.device(), object, light ? "radiance" : "image", ANARI_ARRAY2D, &array);
                    anariCommitParameters(h.device(), object);
                    if (light) return Additions{{}, {}, {ANARILight(object)}};
                    ANARIMaterial material = h.keep(anariNewMaterial(h.device(), "matte"));
                    anariSetParameter(h.device(), material, "color", ANARI_SAMPLER, &object);
                    anariCommitParameters(h.device(), material);
                    return Additions{
                        {geometrySurface(h, "sphere", {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kPoints)}},
                                         {{"radius", 0.2f}}, material)},
                        {},
                        {}};
                }
                ANARIArray1D array = h.keep(anariNewArray1D(h.device(), nullptr, nullptr, nullptr, type, 4));
                std::vector<std::pair<const char*, ANARIArray1D>> arrays = {{parameter, array}};
                if (std::string(parameter) != "vertex.position")
                    arrays.push_back({"vertex.position", h.array(ANARI_FLOAT32_VEC3, kQuadCorners)});
                return Additions{{geometrySurface(h, subtype, arrays, {{"radius", 0.2f}})}, {}, {}};
            },
            std::string(subtype) == "image2D" ? "white spheres" : "",
            quick};
}

std::vector<BadCase> allCases() {
    std::vector<BadCase> cases;
    const std::vector<float> kinds = {kNaN, kInf, -kInf};
    for (float bad : kinds) {
        const bool quick = std::isnan(bad);  // the tests sweep NaN (and +-Inf for two); the program all three
        const std::vector<glm::vec4> colors(4, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
        cases.push_back(meshArrayCase("vertex.position", ANARI_FLOAT32_VEC3, kQuadCorners, bad, true));
        cases.push_back(
            meshArrayCase("vertex.normal", ANARI_FLOAT32_VEC3, std::vector<glm::vec3>(4, {0, 0, 1}), bad, quick));
        cases.push_back(meshArrayCase("vertex.color", ANARI_FLOAT32_VEC4, colors, bad, quick));
        for (const char* attribute :
             {"vertex.attribute0", "vertex.attribute1", "vertex.attribute2", "vertex.attribute3"})
            cases.push_back(meshArrayCase(attribute, ANARI_FLOAT32_VEC4, colors, bad, false));
        cases.push_back(meshArrayCase("primitive.color", ANARI_FLOAT32_VEC4, std::vector<glm::vec4>(2, glm::vec4(0.5f)),
                                      bad, false));
        cases.push_back(pointArrayCase("sphere", "vertex.position", bad, quick));
        cases.push_back(pointArrayCase("sphere", "vertex.radius", bad, quick));
        cases.push_back(pointArrayCase("cylinder", "primitive.radius", bad, false));
        cases.push_back(pointArrayCase("cone", "vertex.radius", bad, false));
        cases.push_back(pointArrayCase("curve", "vertex.position", bad, false));
        cases.push_back(lightCase("directional", "direction", 3, bad, false));
        cases.push_back(lightCase("directional", "irradiance", 1, bad, true));
        cases.push_back(lightCase("directional", "angularDiameter", 1, bad, quick));
        cases.push_back(lightCase("directional", "color", 3, bad, false));
        cases.push_back(lightCase("point", "position", 3, bad, false));
        cases.push_back(lightCase("point", "intensity", 1, bad, false));
        cases.push_back(lightCase("quad", "edge1", 3, bad, false));
        cases.push_back(lightCase("spot", "openingAngle", 1, bad, quick));
        cases.push_back(lightCase("hdri", "scale", 1, bad, false));
        cases.push_back(hdriTexelCase(bad, quick));
        cases.push_back(instanceCase(bad, quick));
        cases.push_back(samplerCase("image2D", "image", bad, quick));
        cases.push_back(samplerCase("image2D", "outTransform", bad, false));
        cases.push_back(samplerCase("primitive", "array", bad, false));
        cases.push_back(samplerCase("transform", "outTransform", bad, false));
        cases.push_back(materialCase("matte", "color", 3, bad, quick));
        cases.push_back(materialCase("physicallyBased", "emissive", 3, bad, false));
        cases.push_back(materialCase("physicallyBased", "roughness", 1, bad, false));
    }
    using V3 = glm::uvec3;
    cases.push_back(indexCase("triangle", ANARI_UINT32_VEC3, std::vector<V3>{{0, 1, 2}, {0, 2, 7}},
                              "element 1 refers to vertex 7, but there are 4 vertices; 1 of 2", true));
    cases.push_back(indexCase("triangle", ANARI_INT32_VEC3, std::vector<glm::ivec3>{{0, 1, 2}, {0, -1, 3}},
                              "element 1 refers to vertex -1 or below", true));
    cases.push_back(indexCase("quad", ANARI_UINT32_VEC4, std::vector<glm::uvec4>{{0, 1, 2, 9}},
                              "element 0 refers to vertex 9, but there are 4 vertices; 1 of 1", false));
    cases.push_back(indexCase("sphere", ANARI_UINT32, std::vector<uint32_t>{0, 1, 5, 3, 4},
                              "element 2 refers to vertex 5, but there are 4 vertices; 2 of 5", false));
    cases.push_back(indexCase("cylinder", ANARI_UINT32_VEC2, std::vector<glm::uvec2>{{0, 1}, {2, 8}},
                              "element 1 refers to vertex 8, but there are 4 vertices; 1 of 2", false));
    cases.push_back(
        indexCase("curve", ANARI_UINT32, std::vector<uint32_t>{0, 3}, "element 1 starts a segment at vertex 3", false));
    cases.push_back(elementTypeCase("triangle", "vertex.position", ANARI_FLOAT32_VEC2, "FLOAT32_VEC2", true));
    cases.push_back(elementTypeCase("triangle", "primitive.index", ANARI_FLOAT32_VEC3, "FLOAT32_VEC3", false));
    cases.push_back(elementTypeCase("triangle", "vertex.color", ANARI_FLOAT32_BOX1, "FLOAT32_BOX1", false));
    cases.push_back(elementTypeCase("sphere", "vertex.radius", ANARI_FLOAT32_BOX1, "FLOAT32_BOX1", false));
    cases.push_back(elementTypeCase("hdri", "radiance", ANARI_UFIXED8_VEC4, "UFIXED8_VEC4", false));
    cases.push_back(elementTypeCase("image2D", "image", ANARI_FLOAT32_BOX1, "FLOAT32_BOX1", true));
    return cases;
}

// The good scene: a sphere on the left lit by a directional light and a dim ambient, seen from +z.
struct GoodScene {
    ANARICamera camera = nullptr;
    ANARISurface sphere = nullptr;
    ANARILight light = nullptr;
    RenderSettings settings;
};

Image renderWith(Harness& h, const GoodScene& scene, const Additions& added) {
    std::vector<ANARISurface> surfaces = {scene.sphere};
    surfaces.insert(surfaces.end(), added.surfaces.begin(), added.surfaces.end());
    std::vector<ANARILight> lights = {scene.light};
    lights.insert(lights.end(), added.lights.begin(), added.lights.end());
    return h.render(h.world(surfaces, added.instances, lights), scene.camera, scene.settings);
}

}  // namespace

std::vector<Row> badDataCases(Harness& h, bool quick) {
    GoodScene scene;
    scene.camera = h.perspective({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 0.7f);
    scene.sphere = h.surface(h.spheres({{-1.0f, 0.0f, 0.0f}}, 0.7f), h.matte({0.7f, 0.7f, 0.7f}));
    scene.light = h.directional({-0.3f, -0.4f, -1.0f}, 2.0f);
    scene.settings.size = {32, 16};
    scene.settings.pixelSamples = 4;
    scene.settings.maxPathLength = 3;
    scene.settings.ambientRadiance = 0.3f;

    std::map<std::string, Image> references;
    references[""] = renderWith(h, scene, {});
    references["white spheres"] =
        renderWith(h, scene,
                   {{geometrySurface(h, "sphere", {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kPoints)}},
                                     {{"radius", 0.2f}}, h.matte(glm::vec3(1.0f)))},
                    {},
                    {}});

    std::vector<Row> rows;
    // Control: the good twin of the bad mesh is visible, so a bad object that rendered would be seen.
    {
        h.clearMessages();
        Row row{"bad data", "control: the finite triangle quad renders", true, false, true, "", ""};
        const Image image = renderWith(
            h, scene,
            {{geometrySurface(
                 h, "triangle",
                 {{"vertex.position", h.array(ANARI_FLOAT32_VEC3, kQuadCorners)}, {"primitive.index", quadIndex(h)}})},
             {},
             {}});
        const float difference = maxRgbDifference(image, references[""]);
        row.finite = image.nonFinite == 0 && image.rendered;
        row.holds = h.errorCount() == 0 && difference > kVisible;
        row.measured = "errors " + std::to_string(h.errorCount()) + " (want 0), largest pixel difference " +
                       formatNumber(difference) + " (want > " + formatNumber(kVisible) + ")";
        row.why = "the comparison below can see a rendered bad object";
        rows.push_back(row);
    }
    for (const BadCase& badCase : allCases()) {
        if (quick && !badCase.quick) continue;
        h.clearMessages();
        const Image image = renderWith(h, scene, badCase.build(h));
        const std::vector<std::string> messages = h.messages();
        const auto named = std::find_if(messages.begin(), messages.end(), [&](const std::string& message) {
            return std::all_of(badCase.fragments.begin(), badCase.fragments.end(), [&](const std::string& fragment) {
                return message.find(fragment) != std::string::npos;
            });
        });
        const float difference = maxRgbDifference(image, references[badCase.referenceKey]);
        Row row;
        row.group = "bad data";
        row.name = badCase.name;
        row.expected = true;  // exact checks at commit, and a deterministic renderer: nothing to lose precision to
        row.finite = image.rendered && image.nonFinite == 0;
        row.holds = h.errorCount() == 1 && named != messages.end() && difference <= kSameImage;
        row.measured = "errors " + std::to_string(h.errorCount()) +
                       " (want 1, naming object, parameter, where: " + (named != messages.end() ? "yes" : "no") +
                       "), largest pixel difference from the frame without it " + formatNumber(difference) +
                       " (want <= " + formatNumber(kSameImage) + ")";
        row.why = named != messages.end() ? "refused: " + *named
                                          : "no message with: " + badCase.fragments.back() +
                                                (messages.empty() ? "" : "; got: " + messages.front());
        rows.push_back(row);
    }
    return rows;
}

}  // namespace ripple::robustness
