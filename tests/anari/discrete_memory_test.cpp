// The device parameter "discreteMemory": a device given it stages every buffer transfer as on a discrete GPU
// (device property "ripple.discreteMemory") and renders the image of a device without it, bit for bit; set
// after the first render it is reported and changes nothing.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

// A sphere on a floor under a directional light, 32x32 at 4 samples per pixel, linear float colour.
Image renderSphere(RenderSession& s) {
    ANARIFrame frame = s.frame(s.sphereOnFloor(), s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f}),
                               s.renderer(4, 3), {32, 32}, ANARI_FLOAT32_VEC4, true);
    return s.render(frame);
}

// The device's "ripple.discreteMemory", or nothing when it does not answer.
std::optional<bool> discreteMemory(RenderSession& s) {
    int32_t on = -1;
    if (!anariGetProperty(s.device, s.device, "ripple.discreteMemory", ANARI_BOOL, &on, sizeof(on), ANARI_WAIT))
        return std::nullopt;
    return on != 0;
}

}  // namespace

TEST_CASE("device parameter discreteMemory: staged transfers render the mapped image, bit for bit") {
    RenderSession mapped;
    CHECK_FALSE(discreteMemory(mapped).has_value());  // no Vulkan context before the first render
    const Image a = renderSphere(mapped);
    const char* environment = std::getenv("RIPPLE_VK_DISCRETE_MEMORY");
    CHECK(discreteMemory(mapped) == (environment && std::string(environment) == "1"));
    CHECK(mapped.log.problems() == 0);

    RenderSession staged;
    const int32_t on = 1;
    staged.setRaw(staged.device, "discreteMemory", ANARI_BOOL, &on);
    staged.commit(staged.device);
    const Image b = renderSphere(staged);
    CHECK(discreteMemory(staged) == true);
    CHECK(staged.log.problems() == 0);  // the parameter is known, the render clean

    REQUIRE(a.linear.size() == b.linear.size());
    REQUIRE(a.depth.size() == b.depth.size());
    CHECK(std::memcmp(a.linear.data(), b.linear.data(), a.linear.size() * sizeof(glm::vec4)) == 0);
    CHECK(std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0);

    // The context exists now: the parameter cannot change it any more, and says so.
    const int32_t off = 0;
    staged.setRaw(staged.device, "discreteMemory", ANARI_BOOL, &off);
    CHECK(staged.log.count({"discreteMemory", "ignored"}) == 1);
    CHECK(discreteMemory(staged) == true);
}
