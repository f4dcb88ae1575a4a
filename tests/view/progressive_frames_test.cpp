// The viewer's passes through the Ripple device, without a window: a moving pass renders with the device's
// quick-look renderer ("eyeLight") unless the settings turn it off, and a still pass with the path tracer.
// Each is compared with a frame rendered directly through ANARI with that renderer, the same camera and
// size: the random numbers are keyed by pixel and sample, so equal means bit-identical.
#include "apps/common/AnariParams.h"
#include "apps/common/AnariScene.h"
#include "apps/common/AnariSession.h"
#include "apps/common/DemoScene.h"
#include "apps/ripple-view/ProgressiveFrames.h"

#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

using namespace ripple::apps;

namespace {

// One pass of `subtype` at `size`, as the viewer's frames are set up (FLOAT32_VEC4, accumulation on).
std::vector<float> renderDirectly(Session& s, const AnariWorld& scene, const CameraView& view, glm::uvec2 size,
                                  const char* subtype, const ViewerSettings& settings) {
    ANARICamera camera = newAnariCamera(s.device, view, float(size.x) / float(size.y));
    ANARIRenderer renderer = anariNewRenderer(s.device, subtype);
    anari::set(s.device, renderer, "pixelSamples", settings.pixelSamples);
    anari::set(s.device, renderer, "background", settings.background);
    if (std::string(subtype) == "default") {
        anari::set(s.device, renderer, "maxPathLength", settings.maxPathLength);
        anari::set(s.device, renderer, "ambientRadiance", settings.ambientRadiance);
    }
    anariCommitParameters(s.device, renderer);
    ANARIFrame frame = anariNewFrame(s.device);
    const ANARIDataType colorType = ANARI_FLOAT32_VEC4;
    anari::set(s.device, frame, "size", size);
    anariSetParameter(s.device, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    anari::set(s.device, frame, "accumulation", true);
    anari::setObject(s.device, frame, "world", ANARI_WORLD, scene.world);
    anari::setObject(s.device, frame, "renderer", ANARI_RENDERER, renderer);
    anari::setObject(s.device, frame, "camera", ANARI_CAMERA, camera);
    anariCommitParameters(s.device, frame);
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const auto* pixels = static_cast<const float*>(anariMapFrame(s.device, frame, "channel.color", &width, &height, &type));
    std::vector<float> rgba;
    if (pixels && type == ANARI_FLOAT32_VEC4) rgba.assign(pixels, pixels + size_t(width) * height * 4);
    anariUnmapFrame(s.device, frame, "channel.color");
    for (ANARIObject o : {ANARIObject(frame), ANARIObject(renderer), ANARIObject(camera)}) anariRelease(s.device, o);
    return rgba;
}

}  // namespace

TEST_CASE("viewer passes: moving ones with the quick-look renderer (unless turned off), still ones path-traced") {
    Session s;
    StatusLog log{"view test", true, 0};
    openAnariDevice("ripple", log, s);
    const AnariWorld scene = buildDemoScene(s.device, "cornell");
    s.objects.push_back(scene.world);
    const auto [lo, hi] = worldBounds(s.device, scene);
    const glm::uvec2 size{32, 24}, reduced = size / 2u;
    const CameraView view = frameBounds(lo, hi, float(size.x) / float(size.y));
    ViewerSettings settings;
    settings.background = scene.background;
    settings.ambientRadiance = scene.ambientRadiance;

    ProgressiveFrames frames(s, scene, view, size, settings, 2);
    REQUIRE(frames.hasQuickLook());
    REQUIRE(frames.startPass(true));
    REQUIRE(frames.poll(true));
    const std::vector<float> quickLook = frames.latest().rgba;
    CHECK(frames.latest().reduced);
    CHECK(quickLook == renderDirectly(s, scene, view, reduced, "eyeLight", settings));
    CHECK(quickLook != renderDirectly(s, scene, view, reduced, "default", settings));

    settings.quickLookWhileMoving = false;
    frames.setSettings(settings);
    REQUIRE(frames.startPass(true));
    REQUIRE(frames.poll(true));
    CHECK(frames.latest().rgba == renderDirectly(s, scene, view, reduced, "default", settings));

    REQUIRE(frames.startPass(false));
    REQUIRE(frames.poll(true));
    CHECK_FALSE(frames.latest().reduced);
    CHECK(frames.latest().rgba == renderDirectly(s, scene, view, size, "default", settings));
    CHECK(log.errors == 0);
}
