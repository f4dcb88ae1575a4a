// The self-intersection group: shadow acne on a lit plane at every scale, coincident and very thin
// surfaces, needle and zero-area triangles, grazing rays, and rays exactly through shared edges and vertices.
#include "apps/ripple-robustness/Robustness.h"
#include "apps/ripple-robustness/Shapes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace ripple::robustness {
namespace {

// A directional light of irradiance pi straight down on a matte surface of albedo a gives radiance
// a * cos exactly: one shadow ray per sample, so every sample of a lit pixel is the same number and a
// sample lost to acne moves a pixel of n samples by want / n.
constexpr float pi = 3.14159265f;
const glm::vec3 down(0.0f, -1.0f, 0.0f);

// Ripple's ray-origin offset along a normal on one axis (offsetRayOrigin in shaders/sampling.glsl): 256
// float steps of the coordinate, or 2^-16 units where the coordinate is below 1/32 unit; the unit is 1,
// or the world's largest |coordinate| where that is smaller.
double originOffset(double coordinate, double worldMagnitude) {
    const double unit = std::min(1.0, double(float(worldMagnitude)));
    return std::abs(coordinate) < unit / 32.0 ? unit / 65536.0 : 256.0 * floatSpacing(coordinate);
}

// A horizontal square at height y (two triangles).
Mesh square(double y, double halfSize) {
    Mesh m;
    for (glm::dvec2 c : {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
        m.positions.emplace_back(halfSize * c.x, y, halfSize * c.y);
    m.indices = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

ANARISurface meshSurface(Harness& h, const Mesh& m, ANARIMaterial material) {
    return h.surface(h.triangles(m.positions, m.indices), material);
}

// Looks down at 45 degrees from 3 sizes above a plane at height y (30 degree view: it meets the plane
// within 5.2 sizes of the point below the eye).
ANARICamera obliqueCamera(Harness& h, double y, double size) {
    const glm::vec3 eye(glm::dvec3(0.0, y + 3.0 * size, 3.0 * size));
    return h.perspective(eye, glm::vec3(0, -1, -1), glm::vec3(0, 1, 0), glm::radians(30.0f));
}

std::string pixelsOff(uint64_t off, size_t total) {
    return std::to_string(off) + "/" + std::to_string(total) + " px off";
}

Row acneRow(Harness& h, double size, bool grazingLight) {
    Row row;
    row.group = "self-intersection";
    row.name = std::string("plane lit ") + (grazingLight ? "at 5.4 degrees elevation" : "from straight above") +
               ", size " + decade(size);
    const glm::dvec3 toLight = grazingLight ? glm::normalize(glm::dvec3(-1.0, 0.1, -0.3)) : glm::dvec3(0, 1, 0);
    const float want = float(0.5 * toLight.y);
    const float tolerance = 0.002f * want;  // float shading of identical samples: ~1e-6 relative
    // Hit points are interpolated from vertices that share their height, so they are off by a few float
    // steps at most, far inside the 256-step offset: acne-free at any size.
    row.expected = true;
    const double y = 0.37 * size;
    ANARIWorld world = h.world({meshSurface(h, square(y, 20.0 * size), h.matte(glm::vec3(0.5f)))}, {},
                               {h.directional(glm::vec3(-toLight), pi)});
    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 4;
    settings.maxPathLength = 2;
    const Image image = h.render(world, obliqueCamera(h, y, size), settings);
    row.finite = image.nonFinite == 0;
    const Uniformity u = uniformity(image, want, tolerance);
    row.holds = image.rendered && u.outliers == 0;
    row.measured = format("mean %.5f, ", u.mean) + pixelsOff(u.outliers, image.rgba.size()) +
                   format(" (want %.5f +- %.5f each)", want, tolerance);
    row.why = format("offset %.3g of the size vs hit-point error of ~2 float steps",
                     originOffset(y, 20.0 * size) / size);
    return row;
}

// Pixels whose colour is no mix of `a` and `b` (r = t a + (1 - t) b for some t in [0, 1], within tolerance).
uint64_t notAMix(const Image& image, glm::vec3 a, glm::vec3 b, float tolerance) {
    uint64_t off = 0;
    for (const glm::vec4& p : image.rgba) {
        const glm::vec3 d = b - a;
        const float t = std::clamp(glm::dot(glm::vec3(p) - a, d) / glm::dot(d, d), 0.0f, 1.0f);
        const glm::vec3 miss = glm::vec3(p) - (a + t * d);
        if (!(std::max(std::abs(miss.x), std::max(std::abs(miss.y), std::abs(miss.z))) <= tolerance)) ++off;
    }
    return off;
}

Row coincidentRow(Harness& h, bool acrossInstances) {
    Row row;
    row.group = "self-intersection";
    row.name = std::string("coincident quads, red and green") + (acrossInstances ? ", the green one instanced" : "");
    row.expected = true;  // both give the same hit distance; whichever wins, its shadow ray starts 256 steps above both
    const Mesh plane = square(0.37, 20.0);
    ANARISurface red = meshSurface(h, plane, h.matte(glm::vec3(0.8f, 0.0f, 0.0f)));
    ANARISurface green = meshSurface(h, plane, h.matte(glm::vec3(0.0f, 0.8f, 0.0f)));
    std::vector<ANARISurface> surfaces = {red};
    std::vector<ANARIInstance> instances;
    if (acrossInstances) instances.push_back(h.instance(h.group({green}), glm::mat4(1.0f)));
    else surfaces.push_back(green);
    ANARIWorld world = h.world(surfaces, instances, {h.directional(down, pi)});
    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 4;
    const Image image = h.render(world, obliqueCamera(h, 0.37, 1.0), settings);
    row.finite = image.nonFinite == 0;
    const uint64_t off = notAMix(image, {0.8f, 0.0f, 0.0f}, {0.0f, 0.8f, 0.0f}, 0.002f);
    double redSum = 0.0;
    for (const glm::vec4& p : image.rgba) redSum += p.x;
    row.holds = image.rendered && off == 0;
    row.measured = format("red share %.2f, ", redSum / 0.8 / double(std::max<size_t>(1, image.rgba.size()))) +
                   pixelsOff(off, image.rgba.size()) + " (want each a mix of red 0.8 and green 0.8, +- 0.002)";
    row.why = "either surface may win; black or any third colour would be acne or a lost hit";
    return row;
}

// A half-transparent red sheet a gap above an opaque green one, light from above, blue background. The
// camera sees red (half the samples) or, through the sheet, green in its shadow: black. Green light means
// a shadow ray from the green sheet started above the red one; blue means a ray passing through the red
// sheet started below the green one. Both happen once Ripple's origin offset exceeds the gap.
Row thinShellRow(Harness& h, double size, double relativeGap) {
    Row row;
    row.group = "self-intersection";
    row.name = "thin shell, gap " + decade(relativeGap) + " of size " + decade(size);
    const float lower = float(size);
    const float upper = float(size + relativeGap * size);
    const double gap = double(upper) - double(lower);  // as the floats hold it
    const double offset = std::max(originOffset(lower, 20.0 * size), originOffset(upper, 20.0 * size));
    row.expected = gap > 2.0 * offset;
    ANARIMaterial sheet = h.matte(glm::vec3(0.8f, 0.0f, 0.0f), 0.5f);
    anariSetParameter(h.device(), sheet, "alphaMode", ANARI_STRING, "blend");  // opacity counts only when blending
    anariCommitParameters(h.device(), sheet);
    ANARIWorld world =
        h.world({meshSurface(h, square(upper, 20.0 * size), sheet),
                 meshSurface(h, square(lower, 20.0 * size), h.matte(glm::vec3(0.0f, 0.8f, 0.0f)))},
                {}, {h.directional(down, pi)});
    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 16;
    settings.maxPathLength = 2;
    settings.background = {0.0f, 0.0f, 1.0f, 1.0f};
    const Image image = h.render(world, obliqueCamera(h, upper, size), settings);
    row.finite = image.nonFinite == 0;
    uint64_t leaks = 0, escapes = 0;
    double red = 0.0;
    for (const glm::vec4& p : image.rgba) {
        leaks += p.y > 1e-6f ? 1 : 0;
        escapes += p.z > 1e-6f ? 1 : 0;
        red += p.x;
    }
    red /= double(std::max<size_t>(1, image.rgba.size()));
    // Red: 4096 samples of 0.8 with probability 1/2: standard deviation 0.006, so 0.04 is 6 of them.
    row.holds = image.rendered && leaks == 0 && escapes == 0 && std::abs(red - 0.4) <= 0.04;
    row.measured = format("red %.3f (want 0.4 +- 0.04); %.0f px with light leaking, %.0f px seeing through (want 0)",
                          red, double(leaks), double(escapes));
    row.why = format("gap %.3g vs origin offset %.3g", gap, offset) +
              (row.expected ? ": resolved" : ": a gap under twice the offset is not resolved");
    return row;
}

// Zero-area triangles must be skipped with a message; needles must render like any other triangle.
std::vector<Row> degenerateRows(Harness& h) {
    Mesh m = square(0.0, 2.0);
    auto add = [&m](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const uint32_t first = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.indices.emplace_back(first, first + 1, first + 2);
    };
    // Zero area: a repeated vertex, three points on a line, one point three times.
    add({0.1f, 0.5f, 0.1f}, {0.1f, 0.5f, 0.1f}, {0.3f, 0.5f, 0.2f});
    add({-0.5f, 0.5f, 0.0f}, {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.0f});
    add({0.2f, 0.5f, -0.2f}, {0.2f, 0.5f, -0.2f}, {0.2f, 0.5f, -0.2f});
    // Needles, horizontal (so their light is the plane's): one 2e5 long and 0.1 wide, crossing the view
    // as a strip, and two of widths 1e-20 and 1e-38 (a denormal), too thin to be hit.
    add({-1e5f, 0.01f, -0.05f}, {1e5f, 0.01f, -0.05f}, {0.0f, 0.01f, 0.05f});
    add({-1.0f, 0.02f, 0.0f}, {1.0f, 0.02f, 0.0f}, {0.0f, 0.02f, 1e-20f});
    add({-1.0f, 0.03f, 0.0f}, {1.0f, 0.03f, 0.0f}, {0.0f, 0.03f, 1e-38f});
    h.clearMessages();
    ANARIWorld world = h.world({meshSurface(h, m, h.matte(glm::vec3(0.5f)))}, {}, {h.directional(down, pi)});
    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 4;
    settings.maxPathLength = 1;  // direct light only: light bounced between strip and plane is real, not 0.5
    const Image image =
        h.render(world, h.perspective({0.0f, 2.0f, 0.0f}, down, {0.0f, 0.0f, -1.0f}, glm::radians(40.0f)), settings);
    const std::string skipped = "skipped 3 zero-area triangle(s)";

    Row zero;
    zero.group = "self-intersection";
    zero.name = "3 zero-area triangles in a mesh";
    zero.expected = true;
    zero.finite = image.nonFinite == 0;
    zero.holds = image.rendered && h.messagesContain(skipped);
    zero.measured =
        h.messagesContain(skipped) ? "message '" + skipped + "'" : "no message naming 3 zero-area triangles";
    zero.why = "refused at commit (exact double cross product of the float corners is zero), the rest renders";

    Row needle;
    needle.group = "self-intersection";
    needle.name = "needle triangles (2e5 x 0.1 across the view; widths 1e-20, 1e-38)";
    needle.expected = true;  // horizontal needles have exact vertical normals in float: cross of (dx, 0, dz)
    needle.finite = zero.finite;
    const Uniformity u = uniformity(image, 0.5f, 0.001f);
    needle.holds = image.rendered && u.outliers == 0;
    needle.measured =
        format("mean %.4f, ", u.mean) + pixelsOff(u.outliers, image.rgba.size()) + " (want 0.5 +- 0.001 each)";
    needle.why = "the needle strip hides its own shadow from the eye above, so every pixel is lit 0.5";
    return {zero, needle};
}

// The eye 1 above a plane, looking down `degrees` with a field of view as wide, so every ray meets the
// plane at 0.5 to 1.5 times that angle (up to 1 / tan(0.005 deg) = 11459 away; the plane reaches 1e6).
Row grazingRow(Harness& h, double degrees) {
    Row row;
    row.group = "self-intersection";
    row.name = "grazing view, " + format("%g", degrees) + " degrees above the plane";
    row.expected = true;  // the hit height is interpolated from equal heights, whatever the ray's angle
    ANARIWorld world =
        h.world({meshSurface(h, square(-1.0, 1e6), h.matte(glm::vec3(0.5f)))}, {}, {h.directional(down, pi)});
    const double angle = glm::radians(degrees);
    RenderSettings settings;
    settings.size = {16, 16};
    settings.pixelSamples = 4;
    const Image image = h.render(world,
                                 h.perspective({0.0f, 0.0f, 0.0f}, glm::vec3(0.0, -std::sin(angle), -std::cos(angle)),
                                               {0.0f, 1.0f, 0.0f}, float(angle)),
                                 settings);
    row.finite = image.nonFinite == 0;
    const Uniformity u = uniformity(image, 0.5f, 0.001f);
    row.holds = image.rendered && u.outliers == 0;
    row.measured =
        format("mean %.4f, ", u.mean) + pixelsOff(u.outliers, image.rgba.size()) + " (want 0.5 +- 0.001 each)";
    row.why = "shadow rays leave 256 float steps above the hit; black pixels would be acne, blue ones misses";
    return row;
}

// Holes: a closed mesh, no light, a blue background: every sample that hits is black, so a pixel with
// any blue saw through the mesh. With a field of view of 1e-8 rad the camera rays spread by at most 5e-9:
// below half a float step of a direction component near 0.58 or 0.71, so toward a corner (1, 1, 1) or an
// edge (1, 1, 0) their x and y components stay equal and every ray passes exactly through it.
Row holeRow(Harness& h, const std::string& name, const Mesh& mesh, glm::vec3 eye, glm::vec3 direction, float fovy,
            glm::uvec2 size) {
    Row row;
    row.group = "self-intersection";
    row.name = name;
    row.expected = true;  // the watertight test computes a shared edge's function identically for both sides
    ANARIWorld world = h.world({meshSurface(h, mesh, h.matte(glm::vec3(0.5f)))}, {}, {});
    RenderSettings settings;
    settings.size = size;
    settings.pixelSamples = 4;
    settings.maxPathLength = 1;
    settings.background = {0.0f, 0.0f, 1.0f, 1.0f};
    const bool vertical = std::abs(direction.y) > 0.9f * glm::length(direction);
    const glm::vec3 up = vertical ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const Image image = h.render(world, h.perspective(eye, direction, up, fovy), settings);
    row.finite = image.nonFinite == 0;
    uint64_t holes = 0;
    for (const glm::vec4& p : image.rgba) holes += p.z > 0.0f ? 1 : 0;
    row.holds = image.rendered && holes == 0;
    row.measured = std::to_string(holes) + "/" + std::to_string(image.rgba.size()) + " px see through (want 0)";
    row.why = "no sample may slip between triangles that share an edge or a corner";
    return row;
}

std::vector<Row> holeRows(Harness& h, bool quick) {
    const Mesh box = cube(glm::dvec3(0.0), 1.0);
    const float needle = 1e-8f;
    const glm::uvec2 small(8, 8);
    struct Bundle {
        const char* name;
        glm::vec3 eye, direction;
        bool quick;
    };
    const Bundle bundles[] = {
        {"ray bundle exactly through a cube corner, from inside", {0, 0, 0}, {1, 1, 1}, true},
        {"ray bundle exactly through a cube corner, from outside", {3, 3, 3}, {-1, -1, -1}, true},
        {"ray bundle exactly through a cube edge, from outside", {3, 3, 0}, {-1, -1, 0}, true},
        {"ray bundle exactly through a cube edge, from inside", {0, 0, 0}, {1, 1, 0}, false},
        {"ray bundle along a face diagonal, from inside", {0, 0, 0}, {1, 0, 0}, false},
        {"ray bundle along a face diagonal, from outside", {0, 0, 3}, {0, 0, -1}, false},
    };
    std::vector<Row> rows;
    for (const Bundle& b : bundles)
        if (b.quick || !quick) rows.push_back(holeRow(h, b.name, box, b.eye, b.direction, needle, small));
    rows.push_back(holeRow(h, "inside an icosphere of 1280 triangles, 90 degree view", icosphere(3),
                           {0.01f, 0.02f, 0.03f}, {0.3f, -0.2f, 1.0f}, glm::radians(90.0f), {32, 32}));
    return rows;
}

}  // namespace

std::vector<Row> intersectionCases(Harness& harness, bool quick) {
    std::vector<Row> rows;
    std::vector<double> sizes = {1e-6, 1.0, 1e7};
    if (!quick) {
        sizes.clear();
        for (int e = -6; e <= 7; ++e) sizes.push_back(std::pow(10.0, e));
    }
    for (double size : sizes)
        for (bool grazing : {false, true}) rows.push_back(acneRow(harness, size, grazing));
    rows.push_back(coincidentRow(harness, false));
    rows.push_back(coincidentRow(harness, true));
    for (double size : quick ? std::vector<double>{1.0} : std::vector<double>{1e-6, 1e-3, 1.0, 1e3})
        for (double gap : {1e-4, 1e-5, 1e-6}) rows.push_back(thinShellRow(harness, size, gap));
    if (quick) rows.push_back(thinShellRow(harness, 1e-6, 1e-4));  // a world far below one unit
    for (Row& row : degenerateRows(harness)) rows.push_back(std::move(row));
    for (double degrees : quick ? std::vector<double>{1.0, 0.01} : std::vector<double>{10.0, 1.0, 0.1, 0.01})
        rows.push_back(grazingRow(harness, degrees));
    for (Row& row : holeRows(harness, quick)) rows.push_back(std::move(row));
    return rows;
}

}  // namespace ripple::robustness
