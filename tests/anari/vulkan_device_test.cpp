// The device property "ripple.vulkanDevices" (the Vulkan devices the device sees, the one it renders with
// marked) and the device parameter "vulkanDevice" that overrides the choice: by name, naming a device that
// does not exist (the render fails with the list), and set after the first render (reported, ignored).
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using ripple::test::RenderSession;

namespace {

std::string vulkanDevices(RenderSession& s) {
    const char* text = nullptr;
    if (!anariGetProperty(s.device, s.device, "ripple.vulkanDevices", ANARI_STRING, &text, sizeof(text), ANARI_WAIT) ||
        !text)
        return {};
    return text;
}

size_t occurrences(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

// A small frame of a floor under a directional light, rendered once; whether it has an image.
bool renderFloor(RenderSession& s) {
    const std::vector<ANARISurface> surfaces = {s.surface(s.floor(), s.matte(glm::vec3(0.7f)))};
    const std::vector<ANARILight> lights = {s.directional({0.0f, -1.0f, 0.0f}, 2.0f)};
    ANARIFrame frame = s.frame(s.world(surfaces, lights), s.perspective({0.0f, 2.0f, 4.0f}, {0.0f, 0.0f, 0.0f}),
                               s.renderer(1, 2), {8, 8}, ANARI_FLOAT32_VEC4);
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const bool mapped = anariMapFrame(s.device, frame, "channel.color", &width, &height, &type) != nullptr;
    if (mapped) anariUnmapFrame(s.device, frame, "channel.color");
    return mapped && width == 8 && height == 8;
}

}  // namespace

TEST_CASE("device property ripple.vulkanDevices lists the devices and marks the one rendering, before and after") {
    RenderSession s;
    const std::string before = vulkanDevices(s);
    CAPTURE(before);
    CHECK(occurrences(before, "[chosen]") == 1);
    CHECK(before.rfind("0: ", 0) == 0);  // indexed from 0, one device a line
    CHECK(occurrences(before, "), driver ") >= 1);
    CHECK(renderFloor(s));
    CHECK(s.log.problems() == 0);
    CHECK(vulkanDevices(s) == before);  // the device it renders with is the one it said it would take
}

TEST_CASE("device parameter vulkanDevice: chooses by name, refuses what matches nothing, is fixed by the first render") {
    RenderSession byName;
    byName.set(byName.device, "vulkanDevice", "llvmpipe");  // lavapipe, which CI has; any device's name would do
    byName.commit(byName.device);
    const std::string listed = vulkanDevices(byName);
    CAPTURE(listed);
    if (listed.find("llvmpipe") == std::string::npos) {
        MESSAGE("no lavapipe device here: the by-name case is skipped");
    } else {
        CHECK(listed.find("chosen by the device parameter vulkanDevice \"llvmpipe\"") != std::string::npos);
        CHECK(renderFloor(byName));
        CHECK(byName.log.problems() == 0);
    }
    byName.set(byName.device, "vulkanDevice", "0");
    CHECK(byName.log.count({"vulkanDevice", "ignored"}) == (listed.find("llvmpipe") == std::string::npos ? 0 : 1));

    RenderSession none;
    none.set(none.device, "vulkanDevice", "no-such-gpu");
    none.commit(none.device);
    CHECK(vulkanDevices(none).find("[chosen]") == std::string::npos);
    CHECK_FALSE(renderFloor(none));  // the frame reports the error and has no image
    CHECK(none.log.count({"the device parameter vulkanDevice \"no-such-gpu\" matches no Vulkan device"}) >= 1);
}
