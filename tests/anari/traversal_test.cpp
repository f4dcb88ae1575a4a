// The device parameter "traversal": its values, the error for an unknown one, the back-end each value
// traces with (the frame property "ripple.traversal"), and the same image from each. "auto" is
// RIPPLE_TRAVERSAL when set, else the device's choice: software on lavapipe. anari_render_ray_query runs
// these with RIPPLE_TRAVERSAL=rayQuery, so there "auto" is ray queries.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>
#include <vector>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

struct Traced {
    Image image;
    std::string traversal;  // the frame's "ripple.traversal"
};

// A sphere on a floor under a directional light, 64x64 at 16 samples per pixel, 8-bit sRGB.
Traced renderSphere(RenderSession& s) {
    ANARIFrame frame = s.frame(s.sphereOnFloor(), s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f}),
                               s.renderer(16, 3), {64, 64}, ANARI_UFIXED8_RGBA_SRGB);
    Traced traced{s.render(frame), {}};
    const char* name = nullptr;
    if (anariGetProperty(s.device, frame, "ripple.traversal", ANARI_STRING, &name, sizeof(name), ANARI_WAIT) && name)
        traced.traversal = name;
    return traced;
}

// Renders the sphere with the device parameter set to `value`.
Traced renderWith(const char* value, uint64_t* problems) {
    RenderSession s;
    s.set(s.device, "traversal", value);
    s.commit(s.device);
    Traced traced = renderSphere(s);
    *problems = s.log.problems();
    return traced;
}

}  // namespace

TEST_CASE("device parameter traversal: an unknown value is reported, naming it and the allowed ones") {
    RenderSession s;
    s.set(s.device, "traversal", "hardware");
    s.commit(s.device);
    CHECK(s.log.count({"traversal", "'hardware'", "auto, software, rayQuery"}) == 1);
}

// The same seed draws the same random numbers in each, and the back-ends' hits differ at most in the last
// bits of t and u/v (tests/unit/ray_query_test.cpp), so the 8-bit images agree to RMSE 0.002 (linear RGB),
// a tenth of what 16 more samples change (tests/anari/render_test.cpp: 0.02 at 16 samples).
TEST_CASE("device parameter traversal: each value traces with its back-end, and all render the same image") {
    uint64_t problems = 0;
    const Traced software = renderWith("software", &problems);
    CHECK(problems == 0);
    CHECK(software.traversal == "software");

    const Traced byDefault = renderWith("auto", &problems);
    CHECK(problems == 0);
    const char* forced = std::getenv("RIPPLE_TRAVERSAL");
    CHECK(byDefault.traversal == (forced ? forced : "software"));  // lavapipe is a CPU device
    CHECK(ripple::test::rmseRgb(software.image, byDefault.image) < 0.002);

    // Ray queries where the driver has them (Mesa 25's lavapipe does; the ray_query suite says where not).
    const Traced rayQuery = renderWith("rayQuery", &problems);
    if (problems > 0) {
        MESSAGE("no ray queries on this device: the rayQuery value was refused");
    } else {
        CHECK(rayQuery.traversal == "rayQuery");
        CHECK(ripple::test::rmseRgb(software.image, rayQuery.image) < 0.002);
    }
}
