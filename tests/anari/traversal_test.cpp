// The device parameter "traversal": its values, the error for an unknown one, and the same image from the
// software traversal and from "auto" (RIPPLE_TRAVERSAL when set, else the device's choice: software on
// lavapipe). anari_render_ray_query runs these with RIPPLE_TRAVERSAL=rayQuery, so there "auto" is ray queries.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <vector>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

// A sphere on a floor under a directional light, 64x64 at 16 samples per pixel, 8-bit sRGB.
Image renderSphere(RenderSession& s) {
    ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
    s.setObject(sphere, "vertex.position", ANARI_ARRAY1D,
                s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0.0f, 0.6f, 0.0f}}));
    s.set(sphere, "radius", 0.6f);
    s.commit(sphere);
    const std::vector<ANARISurface> surfaces = {s.surface(sphere, s.matte({0.2f, 0.5f, 0.8f})),
                                                s.surface(s.floor(), s.matte(glm::vec3(0.7f)))};
    const std::vector<ANARILight> lights = {s.directional(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.4f)), 3.0f)};
    return s.render(s.frame(s.world(surfaces, lights), s.perspective({0.0f, 1.6f, 4.0f}, {0.0f, 0.5f, 0.0f}),
                            s.renderer(16, 3), {64, 64}, ANARI_UFIXED8_RGBA_SRGB));
}

}  // namespace

TEST_CASE("device parameter traversal: an unknown value is reported, naming it and the allowed ones") {
    RenderSession s;
    s.set(s.device, "traversal", "hardware");
    s.commit(s.device);
    CHECK(s.log.count({"traversal", "'hardware'", "auto, software, rayQuery"}) == 1);
}

// The same seed draws the same random numbers in both, and the back-ends' hits differ at most in the last
// bits of t and u/v (tests/unit/ray_query_test.cpp), so the 8-bit images agree to RMSE 0.002 (linear RGB),
// a tenth of what 16 more samples change (tests/anari/render_test.cpp: 0.02 at 16 samples).
TEST_CASE("device parameter traversal: software and the default render the same image") {
    Image software, byDefault;
    {
        RenderSession s;
        s.set(s.device, "traversal", "software");
        s.commit(s.device);
        software = renderSphere(s);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    }
    {
        RenderSession s;
        s.set(s.device, "traversal", "auto");
        s.commit(s.device);
        byDefault = renderSphere(s);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    }
    CHECK(ripple::test::rmseRgb(software, byDefault) < 0.002);
}
