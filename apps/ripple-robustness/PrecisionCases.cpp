// The "scale x translation" group: a white furnace (matte albedo a in uniform ambient radiance L, no lights)
// for a sphere, a triangle cube and an instanced cube, each of size 1e-6 .. 1e7 placed at 0 .. 1e7.
#include "apps/ripple-robustness/Robustness.h"
#include "apps/ripple-robustness/Shapes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace ripple::robustness {
namespace {

// A convex closed object in a uniform environment: every camera ray hits it (the view is filled), the
// bounce leaves it and sees L, so each sample is exactly a * L whatever the direction sampled: no noise,
// and a tight tolerance. A sample that slips through a hole sees the background L; one that starts on
// the wrong side of the surface is trapped inside and ends darker. Both move a pixel of 4 samples by at
// least a * L / 8 = 0.0625, far outside the tolerance.
constexpr float albedo = 0.5f;
constexpr float ambient = 1.0f;
constexpr float want = albedo * ambient;
constexpr float tolerance = 0.005f;  // 1 % of a * L: float accumulation of 4 exact samples is far inside
// Geometry rounds to the float spacing at the largest coordinate; relative to the object that error is
// spacing / size. At 2^-10 or below, the camera moves by < 0.001 of the object (its view keeps a margin of
// a third of the object), normals tilt by < 0.001 rad (the cosine lobe loses O(1e-6) below the true
// horizon), so the tolerance must hold; beyond it nothing is promised.
constexpr double precisionLimit = 1.0 / 1024.0;

enum class Shape { Sphere, Cube, InstancedCube };

const char* shapeName(Shape shape) {
    switch (shape) {
    case Shape::Sphere: return "sphere";
    case Shape::Cube: return "triangle cube";
    case Shape::InstancedCube: return "instanced cube";
    }
    return "";
}

struct View {
    glm::dvec3 eyeOffset;  // from the object's centre, in object sizes
    glm::vec3 direction;
    float fovy;
};

// The sphere (radius 1) from 3 radii away fills a cone of 19.5 degrees half-angle; the 16 degree view
// reaches 11.3 degrees at its corners. The cube (half-size 1) is seen face-on from 2 away: the 30 degree
// view covers 0.55 of the face's half-width of 1.
View viewOf(Shape shape) {
    if (shape == Shape::Sphere) {
        const glm::dvec3 away = glm::normalize(glm::dvec3(0.3, 0.4, 1.0));
        return {3.0 * away, glm::vec3(-away), glm::radians(16.0f)};
    }
    return {glm::dvec3(0.1, 0.2, 3.0), glm::vec3(-0.02f, -0.05f, -1.0f), glm::radians(30.0f)};
}

ANARIWorld furnaceWorld(Harness& h, Shape shape, double scale, glm::dvec3 center) {
    ANARIMaterial material = h.matte(glm::vec3(albedo));
    if (shape == Shape::Sphere) {
        ANARIGeometry sphere = h.spheres({glm::vec3(center)}, float(scale));
        return h.world({h.surface(sphere, material)}, {}, {});
    }
    if (shape == Shape::Cube) {
        const Mesh m = cube(center, scale);
        return h.world({h.surface(h.triangles(m.positions, m.indices), material)}, {}, {});
    }
    const Mesh unit = cube(glm::dvec3(0.0), 1.0);
    ANARIGroup group = h.group({h.surface(h.triangles(unit.positions, unit.indices), material)});
    const glm::mat4 toWorld = glm::mat4(glm::scale(glm::translate(glm::dmat4(1.0), center), glm::dvec3(scale)));
    return h.world({}, {h.instance(group, toWorld)}, {});
}

Row furnaceRow(Harness& h, Shape shape, double scale, double translation) {
    Row row;
    row.group = "scale x translation";
    row.name = std::string(shapeName(shape)) + ", scale " + decade(scale) + ", translation " + decade(translation);
    const glm::dvec3 center(translation);
    const View view = viewOf(shape);
    const glm::dvec3 eye = center + scale * view.eyeOffset;
    const double largest = std::max(std::abs(eye.x), std::max(std::abs(eye.y), std::abs(eye.z))) + scale;
    const double relative = floatSpacing(largest) / scale;
    row.expected = relative <= precisionLimit;

    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 4;
    settings.maxPathLength = 3;
    settings.background = glm::vec4(ambient, ambient, ambient, 1.0f);
    settings.ambientRadiance = ambient;
    h.clearMessages();
    ANARICamera camera = h.perspective(glm::vec3(eye), view.direction, glm::vec3(0, 1, 0), view.fovy);
    const Image image = h.render(furnaceWorld(h, shape, scale, center), camera, settings);
    row.finite = image.nonFinite == 0;
    const Uniformity u = uniformity(image, want, tolerance);
    row.holds = image.rendered && u.outliers == 0;
    row.measured = format("mean %.4f, max |dev| %.2g, %.0f/%.0f px off", u.mean, u.maxDeviation, double(u.outliers),
                          double(image.rgba.size())) +
                   format(" (want %.3f +- %.3f each)", want, tolerance);
    if (!image.rendered)
        row.measured = "no frame: " + (h.messages().empty() ? std::string("no message") : h.messages().front());
    const std::string spacing = "float spacing / size = 2^" + std::to_string(int(std::lround(std::log2(relative))));
    if (!row.expected)
        row.why = spacing + " > 2^-10: camera, surface points and normals round by more than 1/1024 of the object";
    else if (!row.holds)
        row.why = spacing + " <= 2^-10, yet off: a precision bug";
    else
        row.why = spacing + ": within the 2^-10 the tolerance needs";
    return row;
}

}  // namespace

std::vector<Row> precisionCases(Harness& harness, bool quick) {
    std::vector<std::pair<double, double>> points;  // (scale, translation)
    if (quick) {
        // The four corners and the middle of the sweep.
        points = {{1e-6, 0.0}, {1e7, 0.0}, {1e-6, 1e7}, {1e7, 1e7}, {1.0, 1e3}};
    } else {
        for (int s = -6; s <= 7; ++s)
            for (int t = -1; t <= 7; ++t) points.emplace_back(std::pow(10.0, s), t < 0 ? 0.0 : std::pow(10.0, t));
    }
    std::vector<Row> rows;
    for (Shape shape : {Shape::Sphere, Shape::Cube, Shape::InstancedCube})
        for (const auto& [scale, translation] : points) rows.push_back(furnaceRow(harness, shape, scale, translation));
    return rows;
}

}  // namespace ripple::robustness
