// Robustness group "sizes": 1x1 and very large frames, 0 and huge sample counts, near-zero and near-pi
// fields of view, zero-area lights and degenerate camera vectors: each renders right or is refused with a
// message naming the parameter, never a NaN, a crash or a hang.
#include "apps/ripple-robustness/Robustness.h"

#include <glm/gtc/constants.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ripple::robustness {
namespace {

// A matte plane of albedo 0.5 under a directional light of irradiance pi, straight down: every visible point
// sends radiance 0.5 / pi x pi = 0.5 whatever the view direction (Lambertian), one shadow ray per sample, so
// an image of it is 0.5 to float rounding wherever the plane is seen.
constexpr float kRadiance = 0.5f;
constexpr float kUniformTolerance = 1e-4f;

std::string number(double value) { return formatNumber(value, 4); }

// For values that differ in the 5th digit (fovy 3.1415, 3.14158).
std::string preciseNumber(float value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.7g", double(value));
    return text;
}

struct LitPlane {
    ANARISurface ground;
    ANARILight sun;
    ANARIWorld world;
};

LitPlane litPlane(Harness& harness) {
    // 2e6 across seen from height 1: a camera of fovy up to pi - 2.8e-6 (its corner rays meet the plane 1e6
    // away) sees nothing else. Not larger: the triangle test's t sums terms as large as the vertices' distance
    // from the camera times det, so it keeps its sign only while vertices are < ~4e6 x the hit distance away
    // (with 1e7 some rays just off the diagonal at t ~ 1.5 round t to 0 and miss the plane).
    constexpr float half = 1e6f;
    const std::vector<glm::vec3> corners{{-half, -half, 0.0f}, {half, -half, 0.0f}, {half, half, 0.0f}, {-half, half, 0.0f}};
    LitPlane scene;
    scene.ground = harness.surface(harness.triangles(corners, {{0, 1, 2}, {0, 2, 3}}), harness.matte(glm::vec3(0.5f)));
    scene.sun = harness.directional(glm::vec3(0.0f, 0.0f, -1.0f), glm::pi<float>());
    scene.world = harness.world({scene.ground}, {}, {scene.sun});
    return scene;
}

ANARICamera lookingDown(Harness& harness, float fovy) {
    return harness.perspective(glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f), fovy);
}

Row row(const std::string& name, const Image& image) {
    Row r;
    r.group = "sizes";
    r.name = name;
    r.finite = image.nonFinite == 0;
    return r;
}

// A render expected to give the uniform plane; seconds < 0: not timed.
Row uniformRow(const std::string& name, const Image& image, double seconds = -1.0) {
    Row r = row(name, image);
    const Uniformity u = uniformity(image, kRadiance, kUniformTolerance);
    r.holds = image.rendered && u.outliers == 0;
    r.measured = image.rendered ? std::to_string(image.width) + "x" + std::to_string(image.height) + ", mean " +
                                      number(u.mean) + ", " + std::to_string(u.outliers) + " pixels off 0.5 by > 1e-4" +
                                      (seconds >= 0.0 ? ", " + number(seconds) + " s" : "")
                                : "not rendered";
    return r;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void frameSizes(Harness& harness, bool quick, const LitPlane& scene, std::vector<Row>& rows) {
    const ANARICamera camera = lookingDown(harness, 1.0f);
    RenderSettings settings;
    settings.maxPathLength = 1;

    // Memory is about 100 bytes a pixel in the device and the harness's copy: 8192 x 8192 needs 7 GB and
    // lavapipe some tens of seconds, so only the program's full sweep renders it.
    const std::vector<glm::uvec2> sizes = quick ? std::vector<glm::uvec2>{{1, 1}, {1, 64}, {256, 256}}
                                                : std::vector<glm::uvec2>{{1, 1}, {1, 64}, {64, 1}, {1024, 1024}, {4096, 4096}};
    for (glm::uvec2 size : sizes) {
        settings.size = size;
        settings.pixelSamples = size.x * size.y > 4096 ? 1 : 16;
        const auto start = std::chrono::steady_clock::now();
        const Image image = harness.render(scene.world, camera, settings);
        const double seconds = secondsSince(start);
        rows.push_back(uniformRow("frame " + std::to_string(size.x) + "x" + std::to_string(size.y) + ", " +
                                      std::to_string(settings.pixelSamples) + " spp",
                                  image, seconds));
    }

    // The frame limit itself: 16 bytes a pixel make a 4 GiB buffer, past lavapipe's maxBufferSize (2^32 - 1),
    // so it is refused when the frame allocates, naming the buffer; a GPU with larger buffers renders it.
    if (!quick) {
        harness.clearMessages();
        settings.size = {16384, 16384};
        settings.pixelSamples = 1;
        const Image image = harness.render(scene.world, camera, settings);
        Row r = image.rendered ? uniformRow("frame 16384x16384, 1 spp", image) : row("frame 16384x16384, 1 spp", image);
        const bool explained = harness.messagesContain("rendering failed");
        if (!image.rendered) {
            r.holds = explained;
            r.measured = "refused when rendering";
            r.why = explained ? "the device cannot allocate its 4 GiB buffers: 'rendering failed: allocating ... bytes'"
                              : "no frame and no message";
        }
        rows.push_back(r);
    }

    // Beyond what the frame accepts: refused at commit, naming 'size'.
    for (glm::uvec2 size : {glm::uvec2(16385, 1), glm::uvec2(0, 16), glm::uvec2(0xffffffffu, 0xffffffffu)}) {
        harness.clearMessages();
        settings.size = size;
        settings.pixelSamples = 1;
        const Image image = harness.render(scene.world, camera, settings);
        Row r = row("frame " + std::to_string(size.x) + "x" + std::to_string(size.y), image);
        r.holds = !image.rendered && harness.messagesContain("'size'");
        r.measured = image.rendered ? "rendered" : "refused";
        r.why = harness.messagesContain("'size'") ? "refused: parameter 'size' must be between 1x1 and 16384x16384"
                                                  : "no message naming 'size'";
        rows.push_back(r);
    }
}

void sampleCounts(Harness& harness, bool quick, const LitPlane& scene, std::vector<Row>& rows) {
    const ANARICamera camera = lookingDown(harness, 1.0f);
    RenderSettings settings;
    settings.size = {8, 8};
    settings.maxPathLength = 1;

    // The cap (1024 per renderFrame) itself renders; 0, negative and huge counts are refused with a warning
    // naming 'pixelSamples' and the renderer's default (1) is used instead: a frame in moments, never a hang.
    std::vector<int32_t> counts{0, std::numeric_limits<int32_t>::max()};
    if (!quick) counts.insert(counts.end(), {-1, 1025});
    settings.pixelSamples = 1024;
    auto start = std::chrono::steady_clock::now();
    const Image capped = harness.render(scene.world, camera, settings);
    rows.push_back(uniformRow("pixelSamples 1024 (the largest accepted)", capped, secondsSince(start)));
    for (int32_t count : counts) {
        harness.clearMessages();
        settings.pixelSamples = count;
        start = std::chrono::steady_clock::now();
        const Image image = harness.render(scene.world, camera, settings);
        const double seconds = secondsSince(start);
        Row r = uniformRow("pixelSamples " + std::to_string(count), image, seconds);
        const bool named = harness.messagesContain("'pixelSamples'");
        r.holds = r.holds && named && seconds < 30.0;
        r.why = named ? "refused with a warning naming 'pixelSamples' (1..1024); 1 sample used" : "no warning naming 'pixelSamples'";
        rows.push_back(r);
    }
}

void fieldsOfView(Harness& harness, bool quick, const LitPlane& scene, std::vector<Row>& rows) {
    RenderSettings settings;
    settings.maxPathLength = 1;
    // fovy 1e-6 or 1e-30: ray directions differ from (0, 0, -1) by 1e-8 .. 1e-32 in x and y, far above
    // float's smallest normal (1.2e-38), so rays stay distinct and finite and all meet the plane near (0.3,
    // 0.2). Near pi the edge rays meet the plane up to 2.2e5 away at grazing angles; hit points come from
    // barycentrics, so they lie on the plane (z = 0) at any distance, and the shadow ray's origin offset near
    // z = 0 (1/65536) keeps it off the plane: the plane stays uniformly lit.
    std::vector<float> fovs{1e-6f, 3.14f};
    if (!quick) fovs = {1e-30f, 1e-6f, 1e-3f, 3.0f, 3.14f, 3.1415f, 3.14158f};
    for (float fovy : fovs) {
        const auto start = std::chrono::steady_clock::now();
        const Image image = harness.render(scene.world, lookingDown(harness, fovy), settings);
        const double seconds = secondsSince(start);
        rows.push_back(uniformRow("fovy " + preciseNumber(fovy), image, seconds));
    }
    // pi and beyond are not a perspective view: refused with a warning, pi/3 used.
    for (float fovy : quick ? std::vector<float>{glm::pi<float>()} : std::vector<float>{glm::pi<float>(), 4.0f, 0.0f, -1.0f}) {
        harness.clearMessages();
        const Image image = harness.render(scene.world, lookingDown(harness, fovy), settings);
        Row r = uniformRow("fovy " + preciseNumber(fovy), image);
        const bool named = harness.messagesContain("'fovy'");
        r.holds = r.holds && named;
        r.why = named ? "refused with a warning naming 'fovy' (0 < fovy < pi); pi/3 used" : "no warning naming 'fovy'";
        rows.push_back(r);
    }
}

// A quad light of the given edges facing down onto the plane from height 1, with power 1 W.
ANARILight quadLight(Harness& harness, glm::vec3 edge1, glm::vec3 edge2) {
    ANARIDevice d = harness.device();
    ANARILight light = harness.keep(anariNewLight(d, "quad"));
    const glm::vec3 position(0.0f, 0.0f, 1.0f);
    const float power = 1.0f;
    anariSetParameter(d, light, "position", ANARI_FLOAT32_VEC3, &position);
    anariSetParameter(d, light, "edge1", ANARI_FLOAT32_VEC3, &edge1);
    anariSetParameter(d, light, "edge2", ANARI_FLOAT32_VEC3, &edge2);
    anariSetParameter(d, light, "power", ANARI_FLOAT32, &power);
    anariCommitParameters(d, light);
    return light;
}

void zeroAreaLights(Harness& harness, const LitPlane& scene, std::vector<Row>& rows) {
    RenderSettings settings;
    settings.maxPathLength = 1;
    // Straight down onto the plane from (0, 0, 1): the camera sees the light's footprint.
    const ANARICamera camera = harness.perspective(glm::vec3(0.0f, 0.0f, 0.5f), glm::vec3(0.0f, 0.0f, -1.0f),
                                                   glm::vec3(0.0f, 1.0f, 0.0f), 1.0f);
    struct Case {
        const char* name;
        glm::vec3 edge1, edge2;
    };
    // 1e-20 edges: the area 1e-40 is below float's smallest normal and its square underflows to 0.
    const Case cases[] = {{"quad light with a zero edge2", {1e-2f, 0, 0}, {0, 0, 0}},
                          {"quad light with parallel edges", {1e-2f, 0, 0}, {-2e-2f, 0, 0}},
                          {"quad light with edges 1e-20 (area underflows)", {1e-20f, 0, 0}, {0, -1e-20f, 0}}};
    for (const Case& c : cases) {
        harness.clearMessages();
        const ANARIWorld world = harness.world({scene.ground}, {}, {quadLight(harness, c.edge1, c.edge2)});
        const Image image = harness.render(world, camera, settings);
        // No other light: every pixel must be exactly 0 (the refused light is left out, not half-made).
        const Uniformity u = uniformity(image, 0.0f, 0.0f);
        Row r = row(c.name, image);
        const bool named = harness.messagesContain("'edge1'") && harness.messagesContain("'edge2'");
        r.holds = image.rendered && u.outliers == 0 && named;
        r.measured = image.rendered ? "mean " + number(u.mean) + ", " + std::to_string(u.outliers) + " pixels not 0" : "not rendered";
        r.why = named ? "light refused at commit naming 'edge1' and 'edge2'; the world renders without it"
                      : "no message naming 'edge1' and 'edge2'";
        rows.push_back(r);
    }

    // Small but normal: edges 1e-6 (area 1e-12, radiance 1 / (pi 1e-12) = 3e11) light the plane like a point of
    // intensity power / pi: directly below, irradiance (1 / pi) / 1^2, radiance 0.5 / pi^2 = 0.0507.
    const ANARIWorld world = harness.world({scene.ground}, {}, {quadLight(harness, {1e-6f, 0, 0}, {0, -1e-6f, 0})});
    settings.size = {1, 1};
    const ANARICamera narrow = harness.perspective(glm::vec3(0.0f, 0.0f, 0.5f), glm::vec3(0.0f, 0.0f, -1.0f),
                                                   glm::vec3(0.0f, 1.0f, 0.0f), 1e-3f);
    const Image image = harness.render(world, narrow, settings);
    const double want = 0.5 / (glm::pi<double>() * glm::pi<double>());
    const double got = image.rendered ? double(image.rgba[0].x) : 0.0;
    Row r = row("quad light with edges 1e-6 (area 1e-12), power 1", image);
    // The pixel sees the plane within 2.5e-4 of the point below the light: cos^4 falloff < 1e-6.
    r.holds = image.rendered && std::abs(got / want - 1.0) <= 1e-3;
    r.measured = "pixel " + number(got) + " (want " + number(want) + " +- 0.1%)";
    r.why = r.holds ? "" : "a tiny quad light does not deliver its power";
    rows.push_back(r);
}

void degenerateCameras(Harness& harness, const LitPlane& scene, std::vector<Row>& rows) {
    RenderSettings settings;
    settings.size = {8, 8};
    struct Case {
        const char* name;
        glm::vec3 direction, up;
        const char* parameter;  // the message must name it
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Case cases[] = {{"camera direction 0", {0, 0, 0}, {0, 1, 0}, "'direction'"},
                          {"camera up 0", {0, 0, -1}, {0, 0, 0}, "'up'"},
                          {"camera up parallel to direction", {0, 0, -1}, {0, 0, 2}, "parallel"},
                          {"camera direction NaN", {nan, 0, -1}, {0, 1, 0}, "'direction'"}};
    for (const Case& c : cases) {
        harness.clearMessages();
        const ANARICamera camera = harness.perspective(glm::vec3(0.3f, 0.2f, 1.0f), c.direction, c.up, 1.0f);
        const Image image = harness.render(scene.world, camera, settings);
        Row r = row(c.name, image);
        const bool named = harness.messagesContain(c.parameter);
        r.holds = !image.rendered && named;
        r.measured = image.rendered ? "rendered" : "refused";
        r.why = named ? std::string("camera refused at commit, the message names ") + c.parameter
                      : std::string("no message naming ") + c.parameter;
        rows.push_back(r);
    }
    // Only a direction's and up's orientation count: 1e30 and 1e-30 are valid, though their squared lengths
    // (1e60, 1e-60) leave float's range; the device scales by the largest component before normalising.
    settings.maxPathLength = 1;
    for (float length : {1e30f, 1e-30f}) {
        harness.clearMessages();
        const ANARICamera camera = harness.perspective(glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(0.0f, 0.0f, -length),
                                                       glm::vec3(0.0f, length, 0.0f), 1.0f);
        rows.push_back(uniformRow("camera direction and up of length " + number(length),
                                  harness.render(scene.world, camera, settings)));
    }
    // Up 1e-20 away from parallel: accepted (not exactly parallel); the view's right vector, under 1e-6 long,
    // is replaced by a perpendicular of the renderer's choosing (core/render/CameraRays.cpp): no NaN.
    const ANARICamera nearlyParallel = harness.perspective(glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                                                           glm::vec3(1e-20f, 0.0f, 1.0f), 1.0f);
    rows.push_back(uniformRow("camera up 1e-20 from parallel to direction", harness.render(scene.world, nearlyParallel, settings)));
}

}  // namespace

std::vector<Row> extremeSizeCases(Harness& harness, bool quick) {
    std::vector<Row> rows;
    const LitPlane scene = litPlane(harness);
    frameSizes(harness, quick, scene, rows);
    sampleCounts(harness, quick, scene, rows);
    fieldsOfView(harness, quick, scene, rows);
    zeroAreaLights(harness, scene, rows);
    degenerateCameras(harness, scene, rows);
    return rows;
}

}  // namespace ripple::robustness
