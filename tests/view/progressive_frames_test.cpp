// The viewer's passes through the Ripple device, without a window: a moving pass renders with the device's
// quick-look renderer ("eyeLight") unless the settings turn it off, and a still pass with the path tracer;
// the picture of another channel when the settings show one.
// Each is compared with a frame rendered directly through ANARI with that renderer, the same camera and
// size: the random numbers are keyed by pixel and sample (the stratified ones by the sample's place in its
// pass's sequence, the same in both here), so equal means bit-identical.
#include "apps/ripple-view/PassOrders.h"
#include "apps/ripple-view/ProgressiveFrames.h"
#include "apps/scene/AnariParams.h"
#include "apps/scene/AnariScene.h"
#include "apps/scene/AnariSession.h"
#include "apps/scene/DemoScene.h"
#include "apps/scene/SceneEdits.h"

#include <doctest/doctest.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace ripple::apps;

namespace {

// The Ripple device with quiet logging, as each test opens it (the session outlives the test's objects).
struct RippleDevice {
    StatusLog log{"view test", true, 0};
    Session session;
    RippleDevice() { openAnariDevice("ripple", log, session); }
};

// One pass of `subtype` at `size`, as the viewer's frames are set up (FLOAT32_VEC4, accumulation on): the
// colour, or `channel` (channel.normal, FLOAT32_VEC3).
std::vector<float> renderDirectly(Session& s, const AnariWorld& scene, const CameraView& view, glm::uvec2 size,
                                  const char* subtype, const ViewerSettings& settings,
                                  const char* channel = "channel.color") {
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
    const ANARIDataType normalType = ANARI_FLOAT32_VEC3;
    if (std::string(channel) == "channel.normal") anariSetParameter(s.device, frame, channel, ANARI_DATA_TYPE, &normalType);
    anari::set(s.device, frame, "accumulation", true);
    anari::setObject(s.device, frame, "world", ANARI_WORLD, scene.world);
    anari::setObject(s.device, frame, "renderer", ANARI_RENDERER, renderer);
    anari::setObject(s.device, frame, "camera", ANARI_CAMERA, camera);
    anariCommitParameters(s.device, frame);
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const auto* pixels = static_cast<const float*>(anariMapFrame(s.device, frame, channel, &width, &height, &type));
    std::vector<float> values;
    const size_t components = type == ANARI_FLOAT32_VEC4 ? 4 : type == ANARI_FLOAT32_VEC3 ? 3 : 0;
    if (pixels) values.assign(pixels, pixels + size_t(width) * height * components);
    anariUnmapFrame(s.device, frame, channel);
    for (ANARIObject o : {ANARIObject(frame), ANARIObject(renderer), ANARIObject(camera)}) anariRelease(s.device, o);
    return values;
}

}  // namespace

TEST_CASE("viewer passes: moving ones with the quick-look renderer (unless turned off), still ones path-traced") {
    RippleDevice d;
    Session& s = d.session;
    const StatusLog& log = d.log;
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
    CHECK(frames.latest().display.empty());  // the colour is shown

    // Showing the normal channel: the picture is 0.5 n + 0.5 of the frame's normals, the colour unchanged.
    settings.display = DisplayChannel::Normal;
    frames.setSettings(settings);
    REQUIRE(frames.startPass(false));
    REQUIRE(frames.poll(true));
    const std::vector<float> normals = renderDirectly(s, scene, view, size, "default", settings, "channel.normal");
    const PassResult& pass = frames.latest();
    CHECK(pass.rgba == renderDirectly(s, scene, view, size, "default", settings));
    REQUIRE(pass.display.size() == pass.rgba.size());
    REQUIRE(normals.size() * 4 == pass.display.size() * 3);
    size_t wrong = 0;
    for (size_t i = 0; i < normals.size() / 3; ++i)
        for (size_t c = 0; c < 3; ++c) wrong += pass.display[i * 4 + c] != 0.5f * normals[i * 3 + c] + 0.5f ? 1 : 0;
    CHECK(wrong == 0);
    CHECK(log.errors == 0);
}

namespace {

// `passes` full-size passes from a restart; the last one's colour.
std::vector<float> stillImage(ProgressiveFrames& frames, int passes) {
    for (int i = 0; i < passes; ++i) {
        REQUIRE(frames.startPass(false));
        REQUIRE(frames.poll(true));
    }
    return frames.latest().rgba;
}

uint64_t realCollisions(Session& s, ANARIFrame frame) {
    uint64_t count = 0;
    REQUIRE(anariGetProperty(s.device, frame, "ripple.realCollisions", ANARI_UINT64, &count, sizeof count, ANARI_WAIT));
    return count;
}

}  // namespace

// The scene panels' edits (SceneEdits::commit) reach the device between passes and restart the accumulation:
// the Cornell box's one light at twice its radiance gives every pixel twice its value, exactly (the light's
// pick and every path's sampling do not depend on it, and the random numbers restart with the samples).
TEST_CASE("scene edits: a light at twice its radiance doubles every pixel, exactly") {
    RippleDevice d;
    Session& s = d.session;
    const StatusLog& log = d.log;
    SceneEdits edits(s.device);
    const AnariWorld scene = buildDemoScene(s.device, "cornell", {}, &edits);
    s.objects.push_back(scene.world);
    REQUIRE(edits.lights.size() == 1);
    CHECK(edits.lights[0].subtype == "quad");
    CHECK(edits.volumes.empty());
    ViewerSettings settings;
    settings.maxPathLength = 3;
    ProgressiveFrames frames(s, scene, scene.cameras.at(0), {24, 24}, settings, 2);
    const std::vector<float> before = stillImage(frames, 3);
    edits.lights[0].intensity *= 2.0f;
    frames.editScene([&] { edits.commit(edits.lights[0]); });
    const std::vector<float> after = stillImage(frames, 3);
    CHECK(frames.latest().samples == 3);  // restarted
    REQUIRE(after.size() == before.size());
    size_t lit = 0, wrong = 0;
    for (size_t i = 0; i < before.size(); i += 4)
        for (size_t c = 0; c < 3; ++c) {
            lit += before[i + c] > 0.0f ? 1 : 0;
            wrong += after[i + c] != 2.0f * before[i + c] ? 1 : 0;
        }
    CHECK(lit > before.size() / 2);
    CHECK(wrong == 0);
    CHECK(log.errors == 0);
}

// An iso-surface's value moved out of the field's range and back gives the first image again, bit for bit;
// a volume's opacity cleared leaves no real collision in it.
TEST_CASE("scene edits: an isovalue out of range and back, a volume's opacity cleared") {
    RippleDevice d;
    Session& s = d.session;
    const StatusLog& log = d.log;
    const glm::uvec2 size{24, 18};
    ViewerSettings settings;
    settings.maxPathLength = 2;
    {
        SceneEdits edits(s.device);
        const AnariWorld scene = buildDemoScene(s.device, "isosurface", {}, &edits);
        s.objects.push_back(scene.world);
        REQUIRE(edits.isosurfaces.size() == 1);
        CHECK(edits.isosurfaces[0].dataRange.x >= 0.0f);
        CHECK(edits.isosurfaces[0].dataRange.y <= 1.0f);
        ProgressiveFrames frames(s, scene, scene.cameras.at(0), size, settings, 2);
        const std::vector<float> first = stillImage(frames, 2);
        edits.isosurfaces[0].isovalue = 1.5f;  // above every sample: no surface
        frames.editScene([&] { edits.commit(edits.isosurfaces[0]); });
        const std::vector<float> none = stillImage(frames, 2);
        edits.isosurfaces[0].isovalue = 0.5f;
        frames.editScene([&] { edits.commit(edits.isosurfaces[0]); });
        const std::vector<float> again = stillImage(frames, 2);
        CHECK(none != first);
        CHECK(again == first);
    }
    {
        SceneEdits edits(s.device);
        const AnariWorld scene = buildDemoScene(s.device, "volume", {}, &edits);
        s.objects.push_back(scene.world);
        REQUIRE(edits.volumes.size() == 1);
        ProgressiveFrames frames(s, scene, scene.cameras.at(0), size, settings, 2);
        ANARIFrame probe = anariNewFrame(s.device);  // the collision counts of a frame like the viewer's
        const ANARIDataType colorType = ANARI_FLOAT32_VEC4;
        anari::set(s.device, probe, "size", size);
        anariSetParameter(s.device, probe, "channel.color", ANARI_DATA_TYPE, &colorType);
        ANARIRenderer renderer = anariNewRenderer(s.device, "default");
        anariCommitParameters(s.device, renderer);
        ANARICamera camera = newAnariCamera(s.device, scene.cameras.at(0), float(size.x) / float(size.y));
        anari::setObject(s.device, probe, "world", ANARI_WORLD, scene.world);
        anari::setObject(s.device, probe, "renderer", ANARI_RENDERER, renderer);
        anari::setObject(s.device, probe, "camera", ANARI_CAMERA, camera);
        anariCommitParameters(s.device, probe);
        const auto renderProbe = [&] {
            anariRenderFrame(s.device, probe);
            anariFrameReady(s.device, probe, ANARI_WAIT);
            return realCollisions(s, probe);
        };
        stillImage(frames, 1);
        CHECK(renderProbe() > 0);
        std::fill(edits.volumes[0].opacities.begin(), edits.volumes[0].opacities.end(), 0.0f);
        frames.editScene([&] { edits.commit(edits.volumes[0]); });
        stillImage(frames, 1);
        CHECK(renderProbe() == 0);
        for (ANARIObject o : {ANARIObject(probe), ANARIObject(renderer), ANARIObject(camera)}) anariRelease(s.device, o);
    }
    CHECK(log.errors == 0);
}

// Under mpirun rank 0 sends its volume and iso-surface edits to the other ranks, whose records (their own
// slabs of the same scene) take the values: here two builds of one scene stand for two ranks.
TEST_CASE("pass orders: volume and iso-surface edits carried to another rank's records") {
    RippleDevice d;
    Session& s = d.session;
    const StatusLog& log = d.log;
    SceneEdits rank0(s.device), rank1(s.device);
    for (SceneEdits* edits : {&rank0, &rank1}) s.objects.push_back(buildDemoScene(s.device, "volume", {}, edits).world);
    REQUIRE(rank0.volumes.size() == 1);
    EditableVolume& v = rank0.volumes[0];
    v.colors = transferFunctionColors("coolwarm");
    v.opacities = {0.0f, 0.25f, 1.0f};
    v.valueRange = {0.125f, 0.75f};
    v.unitDistance = 0.03f;
    SceneEditRequests requests;
    requests.volumes.insert(0);
    const std::vector<uint8_t> bytes = encodeFieldEdits(rank0, requests);
    const SceneEditRequests received = decodeFieldEdits(bytes, rank1);
    CHECK(received.volumes == requests.volumes);
    CHECK(received.isosurfaces.empty());
    const EditableVolume& w = rank1.volumes[0];
    CHECK(w.colors == v.colors);
    CHECK(w.opacities == v.opacities);
    CHECK(w.valueRange == v.valueRange);
    CHECK(w.unitDistance == v.unitDistance);
    CHECK(w.handle != v.handle);  // its own object
    // An edit of a record the other rank lacks, or a cut message, is refused, not read past its end.
    SceneEdits empty(s.device);
    CHECK_THROWS_WITH_AS(decodeFieldEdits(bytes, empty), "rank 0 edited a volume this rank does not have", std::runtime_error);
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + long(bytes.size() / 2));
    CHECK_THROWS_WITH_AS(decodeFieldEdits(cut, rank1), "rank 0's field edits end early", std::runtime_error);
    CHECK(log.errors == 0);
}

// A pass order's fixed part as broadcast: every field rank 0 sets comes back (a field added to CameraView or
// ViewerSettings and not carried would fail here), and an absent change stays absent.
TEST_CASE("pass orders: encoded and decoded, every field") {
    PassOrder order;
    order.moving = true;
    CameraView view;
    view.orthographic = true;
    view.position = {1.0f, 2.0f, 3.0f};
    view.direction = {0.0f, -0.6f, -0.8f};
    view.up = {0.0f, 0.8f, -0.6f};
    view.fovy = 0.3f;
    view.height = 4.5f;
    view.apertureRadius = 0.25f;
    view.focusDistance = 7.0f;
    ViewerSettings settings;
    settings.pixelSamples = 3;
    settings.maxPathLength = 9;
    settings.background = {0.1f, 0.2f, 0.3f, 0.4f};
    settings.ambientRadiance = 0.7f;
    settings.quickLookWhileMoving = false;
    settings.display = DisplayChannel::InstanceId;
    order.changes = {view, settings, glm::uvec2(640, 360), 4u};
    order.fieldEdits = {1, 2, 3};
    const PassOrder back = decodePassOrder(encodePassOrder(order));
    CHECK_FALSE(back.quit);
    CHECK(back.moving);
    REQUIRE(back.changes.view);
    const CameraView& v = *back.changes.view;
    CHECK(v.orthographic);
    CHECK(v.position == view.position);
    CHECK(v.direction == view.direction);
    CHECK(v.up == view.up);
    CHECK(v.fovy == view.fovy);
    CHECK(v.height == view.height);
    CHECK(v.apertureRadius == view.apertureRadius);
    CHECK(v.focusDistance == view.focusDistance);
    REQUIRE(back.changes.settings);
    CHECK(*back.changes.settings == settings);
    CHECK(back.changes.size == glm::uvec2(640, 360));
    CHECK(back.changes.reducedScale == 4u);
    CHECK(back.fieldEdits.size() == 3);  // sized for the broadcast that fills it
    const PassOrder quit = decodePassOrder(encodePassOrder({true, false, {}, {}}));
    CHECK(quit.quit);
    CHECK_FALSE(quit.changes.view);
    CHECK_FALSE(quit.changes.settings);
    CHECK_FALSE(quit.changes.size);
    CHECK_FALSE(quit.changes.reducedScale);
    CHECK_THROWS_WITH_AS(decodePassOrder(std::vector<uint8_t>(5)), "a pass order of the wrong size", std::runtime_error);
}

// Another rank takes up rank 0's pending changes and restarts where rank 0 restarts, also when a setting
// changed and changed back within one pass (rank 0 restarts then; a setter that drops a value equal to the
// current one would not).
TEST_CASE("pass orders: the other rank's frames restart where rank 0's do") {
    RippleDevice d;
    Session& s = d.session;
    const StatusLog& log = d.log;
    const AnariWorld scene = buildDemoScene(s.device, "cornell");
    s.objects.push_back(scene.world);
    ViewerSettings settings;
    settings.maxPathLength = 2;
    ProgressiveFrames rank0(s, scene, scene.cameras.at(0), {8, 8}, settings, 2),
        other(s, scene, scene.cameras.at(0), {8, 8}, settings, 2, false);
    const auto pass = [&] {
        const PendingChanges changes = rank0.pending();
        REQUIRE(rank0.startPass(false, 0));
        REQUIRE(rank0.poll(true));
        other.apply(changes);
        REQUIRE(other.startPass(false, 0));
        REQUIRE(other.poll(true));
        CHECK(other.fullSamples() == rank0.fullSamples());
    };
    pass();
    pass();
    CHECK(rank0.fullSamples() == 2);
    ViewerSettings changed = settings;
    changed.maxPathLength = 3;
    rank0.setSettings(changed);
    rank0.setSettings(settings);  // back: still pending, so the next pass restarts
    pass();
    CHECK(rank0.fullSamples() == 1);
    CHECK(other.latest().rgba.empty());  // it holds no image
    CHECK(log.errors == 0);
}

TEST_CASE("channel pictures: depth near bright, far dark, none black; ids hashed, none black") {
    const float depth[4] = {2.0f, 4.0f, 3.0f, std::numeric_limits<float>::infinity()};
    const std::vector<float> d = channelPicture(DisplayChannel::Depth, depth, 4);
    CHECK(d[0] == 1.0f);                    // nearest
    CHECK(d[4] == doctest::Approx(0.1f));   // farthest
    CHECK(d[8] == doctest::Approx(0.55f));
    CHECK(d[12] == 0.0f);                   // no hit
    const uint32_t ids[3] = {7, 7, ~0u};
    const std::vector<float> p = channelPicture(DisplayChannel::ObjectId, ids, 3);
    CHECK(std::vector<float>(p.begin(), p.begin() + 4) == std::vector<float>(p.begin() + 4, p.begin() + 8));
    CHECK(p[0] + p[1] + p[2] >= 0.6f);      // kept off black
    CHECK(p[8] + p[9] + p[10] == 0.0f);
}
