// View-state files (apps/scene/ViewState): what is written reads back the same, every malformed file is
// refused with its name and the member at fault, and the panels' values land on the scene's objects.
#include "apps/scene/ViewState.h"
#include "tests/apps/FakeAnari.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace ripple::test;
using ripple::apps::ViewState;

TEST_CASE("view state: written and read back, perspective and orthographic") {
    TempFolder dir;
    for (const bool orthographic : {false, true}) {
        CAPTURE(orthographic);
        ViewState state;
        state.camera.orthographic = orthographic;
        state.camera.position = {1.5f, -2.25f, 3.0f};
        state.camera.direction = {0.0f, 0.6f, -0.8f};
        state.camera.up = {0.0f, 0.8f, 0.6f};
        state.camera.fovy = 0.75f;
        state.camera.height = 2.5f;
        state.camera.apertureRadius = 0.0625f;  // depth of field: perspective only
        state.camera.focusDistance = 3.5f;
        state.renderer = "eyeLight";
        state.pixelSamples = 4;
        state.maxPathLength = 7;
        state.ambientRadiance = 0.125f;
        state.background = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
        state.size = glm::uvec2(320, 200);
        const auto file = dir / "v.json";
        ripple::apps::writeViewState(file, state);
        const ViewState back = ripple::apps::readViewState(file);
        CHECK(back.camera.orthographic == orthographic);
        CHECK(back.camera.position == state.camera.position);
        CHECK(back.camera.direction == state.camera.direction);
        CHECK(back.camera.up == state.camera.up);
        if (orthographic) CHECK(back.camera.height == state.camera.height);
        else CHECK(back.camera.fovy == state.camera.fovy);
        CHECK(back.camera.apertureRadius == (orthographic ? 0.0f : state.camera.apertureRadius));
        CHECK(back.camera.focusDistance == (orthographic ? 1.0f : state.camera.focusDistance));
        CHECK(back.renderer == state.renderer);
        CHECK(back.pixelSamples == state.pixelSamples);
        CHECK(back.maxPathLength == state.maxPathLength);
        CHECK(back.ambientRadiance == state.ambientRadiance);
        CHECK(back.background == state.background);
        CHECK(back.size == state.size);
        CHECK_FALSE(back.traversal);
        CHECK_FALSE(back.lights);
        CHECK_FALSE(back.volumes);
        CHECK_FALSE(back.isosurfaces);
    }
}

TEST_CASE("view state: the panels' values written and read back") {
    TempFolder dir;
    ViewState state;
    state.camera.position = {0.0f, 0.0f, 3.0f};
    state.camera.direction = {0.0f, 0.0f, -1.0f};
    state.camera.up = {0.0f, 1.0f, 0.0f};
    state.traversal = "software";
    state.lights = {{nullptr, "sun", "directional", {1.0f, 0.5f, 0.25f}, 3.5f, glm::vec3(0.0f, -1.0f, 0.5f), 0.0f},
                    {nullptr, "environment", "hdri", glm::vec3(1.0f), 0.75f, std::nullopt, 135.0f}};
    state.volumes = {{nullptr, "volume 0", {{0.0f, 0.1f, 0.2f}, {1.0f, 0.9f, 0.8f}}, {0.0f, 0.25f, 1.0f}, {-1.0f, 2.5f},
                      0.125f, {}, {}, "viridis"}};
    state.isosurfaces = {{nullptr, "isosurface 0", 0.375f, {}}};
    const auto file = dir / "v.json";
    ripple::apps::writeViewState(file, state);
    const ViewState back = ripple::apps::readViewState(file);
    CHECK(back.traversal == state.traversal);
    REQUIRE(back.lights);
    REQUIRE(back.lights->size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        const auto &a = (*back.lights)[i], &b = (*state.lights)[i];
        CHECK(a.label == b.label);
        CHECK(a.color == b.color);
        CHECK(a.intensity == b.intensity);
        CHECK(a.direction == b.direction);
        if (b.subtype == "hdri") CHECK(a.rotationDegrees == b.rotationDegrees);
        else CHECK(std::isnan(a.rotationDegrees));  // not written: the scene's turn stays
    }
    REQUIRE(back.volumes);
    REQUIRE(back.volumes->size() == 1);
    const auto& volume = back.volumes->front();
    CHECK(volume.label == "volume 0");
    CHECK(volume.colors == state.volumes->front().colors);
    CHECK(volume.opacities == state.volumes->front().opacities);
    CHECK(volume.valueRange == glm::vec2(-1.0f, 2.5f));
    CHECK(volume.unitDistance == 0.125f);
    CHECK(volume.colorMap == "viridis");
    REQUIRE(back.isosurfaces);
    REQUIRE(back.isosurfaces->size() == 1);
    CHECK(back.isosurfaces->front().label == "isosurface 0");
    CHECK(back.isosurfaces->front().isovalue == 0.375f);
}

// The scene's records as a scene builder lists them, on fake objects.
// `withLights` false: as a data-parallel rank other than 0 holds it, without the scene's lights.
struct EditableScene {
    ANARIDevice device = newFakeDevice();
    ripple::apps::SceneEdits edits{device};
    ANARILight sun = anariNewLight(device, "directional");
    ANARIVolume volume = anariNewVolume(device, "transferFunction1D");
    ANARIGeometry isosurface = anariNewGeometry(device, "isosurface");
    explicit EditableScene(bool withLights = true) {
        if (withLights)
            edits.add(ripple::apps::EditableLight{sun, "sun", "directional", glm::vec3(1.0f), 1.0f, glm::vec3(0.0f, -1.0f, 0.0f), 0.0f});
        edits.add(ripple::apps::EditableVolume{volume, "volume 0", {glm::vec3(0.5f)}, {1.0f}, {0.0f, 1.0f}, 1.0f, {0.0f, 1.0f}, {}, ""});
        edits.add(ripple::apps::EditableIsosurface{isosurface, "isosurface 0", 0.5f, {0.0f, 1.0f}});
    }
    ~EditableScene() {
        anariRelease(device, sun);
        anariRelease(device, volume);
        anariRelease(device, isosurface);
    }
};

TEST_CASE("view state: the file's light, volume and iso-surface values are set on the scene's objects") {
    TempFolder dir;
    const auto file = dir / "v.json";
    writeText(file, R"({"ripple-view-state": 1,
        "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7},
        "lights": [{"label": "sun", "color": [1, 0.5, 0.25], "intensity": 4, "direction": [0, 0, -2]}],
        "volumes": [{"label": "volume 0", "colors": [[0, 0, 1], [1, 0, 0]], "opacities": [0, 0.5], "valueRange": [0.25, 0.75],
                     "unitDistance": 0.5}],
        "isosurfaces": [{"label": "isosurface 0", "isovalue": 0.125}]})");
    const ViewState state = ripple::apps::readViewState(file);
    EditableScene scene;
    const ripple::apps::SceneEditRequests changed = ripple::apps::applyViewEdits(state, scene.edits, true, file);
    CHECK(changed.lights.size() == 1);
    CHECK(changed.volumes.size() == 1);
    CHECK(changed.isosurfaces.size() == 1);
    scene.edits.commit(changed);
    const FakeObject* sun = fakeObject(scene.sun);
    CHECK(sun->committed);
    CHECK(sun->parameters.at("color").as<glm::vec3>() == glm::vec3(1.0f, 0.5f, 0.25f));
    CHECK(sun->parameters.at("irradiance").as<float>() == 4.0f);
    CHECK(sun->parameters.at("direction").as<glm::vec3>() == glm::vec3(0.0f, 0.0f, -1.0f));
    const FakeObject* volume = fakeObject(scene.volume);
    CHECK(volume->parameters.at("valueRange").as<glm::vec2>() == glm::vec2(0.25f, 0.75f));
    CHECK(volume->parameters.at("unitDistance").as<float>() == 0.5f);
    const FakeObject* colors = volume->parameters.at("color").object;
    REQUIRE(colors != nullptr);
    REQUIRE(colors->count1 == 2);
    CHECK(colors->elements<glm::vec3>()[1] == glm::vec3(1.0f, 0.0f, 0.0f));
    const FakeObject* opacities = volume->parameters.at("opacity").object;
    REQUIRE(opacities != nullptr);
    REQUIRE(opacities->count1 == 2);
    CHECK(opacities->elements<float>()[1] == 0.5f);
    CHECK(fakeObject(scene.isosurface)->parameters.at("isovalue").as<float>() == 0.125f);

    // A rank without the scene's lights skips the file's.
    EditableScene other(false);
    const ripple::apps::SceneEditRequests withoutLights = ripple::apps::applyViewEdits(state, other.edits, false, file);
    CHECK(withoutLights.lights.empty());
    CHECK(withoutLights.volumes.size() == 1);
}

// An environment's turn comes from the file where it has one; a record without "rotation" keeps the scene's
// (--environment-rotation), while its intensity replaces --environment-intensity.
TEST_CASE("view state: an environment light keeps its turn unless the file gives one") {
    TempFolder dir;
    for (const bool turned : {false, true}) {
        CAPTURE(turned);
        const auto file = dir / "v.json";
        writeText(file, std::string(R"({"ripple-view-state": 1,
            "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7},
            "lights": [{"label": "environment", "color": [1, 1, 1], "intensity": 2)") +
                            (turned ? R"(, "rotation": 90}]})" : "}]}"));
        ANARIDevice device = newFakeDevice();
        ripple::apps::SceneEdits edits(device);
        ANARILight environment = anariNewLight(device, "hdri");
        edits.add(ripple::apps::EditableLight{environment, "environment", "hdri", glm::vec3(1.0f), 1.0f, std::nullopt, 30.0f});
        anariRelease(device, environment);
        ripple::apps::applyViewEdits(ripple::apps::readViewState(file), edits, true, file);
        CHECK(edits.lights[0].intensity == 2.0f);
        CHECK(edits.lights[0].rotationDegrees == (turned ? 90.0f : 30.0f));
    }
}

TEST_CASE("view state: panel values for another scene are refused, naming the list") {
    TempFolder dir;
    const std::string head = R"({"ripple-view-state": 1,
        "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7}, )";
    std::string text, expected;
    SUBCASE("more lights") {
        text = head + R"("lights": [{"label": "sun", "color": [1, 1, 1], "intensity": 1},
                                    {"label": "quad light", "color": [1, 1, 1], "intensity": 1}]})";
        expected = "the view file lists 2 light(s), the scene has 1";
    }
    SUBCASE("another label") {
        text = head + R"("isosurfaces": [{"label": "isosurface 7", "isovalue": 0.5}]})";
        expected = "isosurface 0 is \"isosurface 7\" in the view file but \"isosurface 0\" in the scene";
    }
    const auto file = dir / "v.json";
    writeText(file, text);
    const ViewState state = ripple::apps::readViewState(file);
    EditableScene scene;
    std::string message;
    try {
        ripple::apps::applyViewEdits(state, scene.edits, true, file);
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    INFO("message: " << message);
    CHECK(message.find(file.string() + ": ") == 0);
    CHECK(message.find(expected) != std::string::npos);
}

TEST_CASE("view state: malformed files are refused, naming the file and the member") {
    TempFolder dir;
    const std::string camera = R"("camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7})";
    std::string text, expected;
    SUBCASE("no such file") { expected = "cannot open the view file"; }
    SUBCASE("not JSON") { text = "{\"ripple-view-state\": 1,"; expected = "not JSON"; }
    SUBCASE("no version") { text = "{" + camera + "}"; expected = "missing \"ripple-view-state\""; }
    SUBCASE("another version") { text = "{\"ripple-view-state\": 2, " + camera + "}"; expected = "view-state version 2"; }
    SUBCASE("no camera") { text = R"({"ripple-view-state": 1})"; expected = "missing \"camera\""; }
    SUBCASE("unknown camera type") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "fisheye"}})";
        expected = "\"camera.type\" must be \"perspective\" or \"orthographic\"";
    }
    SUBCASE("short position") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7}})";
        expected = "\"camera.position\" must be an array of 3 numbers";
    }
    SUBCASE("up along the direction") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 0, 2], "fovy": 0.7}})";
        expected = "\"camera.up\" must not be zero, overflow or lie along the direction";
    }
    SUBCASE("a direction whose length overflows") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [1e20, 0, 0], "up": [0, 1, 0], "fovy": 0.7}})";
        expected = "\"camera.direction\" must not be zero or overflow";
    }
    SUBCASE("field of view out of range") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 4}})";
        expected = "\"camera.fovy\" must be within (0, pi) radians";
    }
    SUBCASE("a negative aperture") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7, "apertureRadius": -0.1}})";
        expected = "\"camera.apertureRadius\" must not be negative";
    }
    SUBCASE("a focus distance of zero") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "perspective", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "fovy": 0.7, "apertureRadius": 0.1, "focusDistance": 0}})";
        expected = "\"camera.focusDistance\" must be positive";
    }
    SUBCASE("orthographic without height") {
        text = R"({"ripple-view-state": 1, "camera": {"type": "orthographic", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0]}})";
        expected = "missing \"height\" in an orthographic \"camera\"";
    }
    SUBCASE("a path length of 0") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"renderer\": {\"maxPathLength\": 0}}";
        expected = "\"renderer.maxPathLength\" is 0, not within 1..1024";
    }
    SUBCASE("a non-integer sample count") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"renderer\": {\"pixelSamples\": 1.5}}";
        expected = "\"renderer.pixelSamples\" must be an integer";
    }
    SUBCASE("negative ambient radiance") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"renderer\": {\"ambientRadiance\": -1}}";
        expected = "\"renderer.ambientRadiance\" must not be negative";
    }
    SUBCASE("a light without a label") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"lights\": [{\"color\": [1, 1, 1], \"intensity\": 1}]}";
        expected = "missing \"label\" in \"lights[0]\"";
    }
    SUBCASE("a negative light intensity") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"lights\": [{\"label\": \"sun\", \"color\": [1, 1, 1], \"intensity\": -1}]}";
        expected = "\"lights[0]\" must not have a negative colour or intensity";
    }
    const std::string volume = R"("label": "volume 0", "colors": [[1, 1, 1]], "valueRange": [0, 1])";
    SUBCASE("an empty opacity curve") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"volumes\": [{" + volume + ", \"opacities\": [], \"unitDistance\": 1}]}";
        expected = "\"volumes[0].opacities\" must be an array of 1 to 65536 entries";
    }
    SUBCASE("an opacity above 1") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"volumes\": [{" + volume + ", \"opacities\": [0, 2], \"unitDistance\": 1}]}";
        expected = "\"volumes[0].opacities\" must lie within 0..1";
    }
    SUBCASE("a unit distance of zero") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"volumes\": [{" + volume + ", \"opacities\": [1], \"unitDistance\": 0}]}";
        expected = "\"volumes[0].unitDistance\" must be positive";
    }
    SUBCASE("an inverted value range") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"volumes\": [{\"label\": \"v\", \"colors\": [[1, 1, 1]], \"opacities\": [1], "
               "\"valueRange\": [1, 0], \"unitDistance\": 1}]}";
        expected = "\"volumes[0].valueRange\" must not be inverted";
    }
    SUBCASE("an isovalue past a double") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"isosurfaces\": [{\"label\": \"i\", \"isovalue\": 1e999}]}";
        expected = "not JSON: [json.exception.out_of_range.406] number overflow";
    }
    SUBCASE("an isovalue past a float") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"isosurfaces\": [{\"label\": \"i\", \"isovalue\": 1e300}]}";
        expected = "\"isosurfaces[0].isovalue\" must be finite";
    }
    SUBCASE("an unknown traversal") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"renderer\": {\"traversal\": \"fast\"}}";
        expected = "\"renderer.traversal\" must be \"auto\", \"software\" or \"rayQuery\"";
    }
    SUBCASE("a size of zero") {
        text = "{\"ripple-view-state\": 1, " + camera + ", \"size\": [0, 10]}";
        expected = "\"size[0]\" is 0, not within 1..16384";
    }
    const auto file = dir / "bad.json";
    if (!text.empty()) writeText(file, text);
    std::string message;
    try {
        ripple::apps::readViewState(file);
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    INFO("message: " << message);
    CHECK(message.find(file.string() + ": ") == 0);
    CHECK(message.find(expected) != std::string::npos);
}
