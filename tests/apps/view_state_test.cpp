// View-state files (apps/common/ViewState): what is written reads back the same, and every malformed file
// is refused with its name and the member at fault.
#include "apps/common/ViewState.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

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
    }
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
