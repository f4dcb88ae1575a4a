// ripple-view: an interactive viewer of a glTF file or a built-in demo scene through any ANARI library. Passes
// render progressively while the view is still and at half size while it moves (with the device's quick-look
// renderer, where it has one); panels set the renderer and camera. --screenshot renders a fixed number of passes, writes the image and exits.
// Under mpirun (data-parallel ANARI) every rank imports its share of the glTF file; rank 0 owns the window
// and sends the others each pass's changes (PassOrders.h); the composite shows on rank 0.
#include "apps/ripple-view/OrbitCamera.h"
#include "apps/ripple-view/PassOrders.h"
#include "apps/ripple-view/ProgressiveFrames.h"
#include "apps/ripple-view/ScenePanels.h"
#include "apps/ripple-view/ViewerPanels.h"
#include "apps/ripple-view/ViewerWindow.h"
#include "apps/scene/AnariSession.h"
#include "apps/scene/DemoScene.h"
#include "apps/scene/EnvironmentOptions.h"
#include "apps/scene/ImageSize.h"
#include "apps/scene/SceneEdits.h"
#include "apps/scene/ScenePartition.h"
#include "apps/scene/ViewState.h"
#include "apps/scene/VolumeOptions.h"
#include "io/gltf/GltfScene.h"
#include "io/image/OutputImage.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace ripple::apps {
namespace {

struct Options {
    std::string scene;
    std::string demo;
    std::string library = "ripple";
    std::string size = "800x600";
    int32_t samplesPerPass = 1;
    int32_t maxPathLength = 5;
    std::string screenshot;             // with --frames: render that many passes, write this, exit
    uint32_t frames = 16;
    bool noQuickLook = false;           // moving passes path-traced too
    std::string view;                   // view-state file: read at start when it exists, written by V
    bool sizeGiven = false;             // --size on the command line (else the view file's size, if any)
    bool samplesGiven = false, pathLengthGiven = false;
    std::optional<int> camera;
    std::string partition = "round-robin";  // under mpirun: how the glTF file is split over the ranks
    VolumeOptions field;                // --volume: a scalar field drawn as a volume and/or isosurfaces
    EnvironmentOptions environment;     // an hdri light (rank 0 holds it)
    bool quiet = false;
};

// How long the view counts as moving after its last change: passes stay at reduced size until then.
constexpr double kSettleSeconds = 0.25;

// A file name for the P key (PNG) or shift+P (EXR: the linear, unclipped image) that does not overwrite an
// earlier screenshot.
std::filesystem::path nextScreenshotName(bool exr) {
    for (int i = 0;; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "ripple-view-%03d.%s", i, exr ? "exr" : "png");
        if (!std::filesystem::exists(name)) return name;
    }
}

// `milliseconds`: the mean full-size pass after the first (which creates the device's pipelines); NaN: none.
void writeScreenshot(const std::filesystem::path& file, const PassResult& pass, const ErrorEstimate& estimate,
                     double milliseconds) {
    writeOutputImage(file, outputFormatOf(file, "--screenshot"), pass.size.x, pass.size.y, pass.rgba.data());
    std::printf("wrote %s (%ux%u, %u spp", file.c_str(), pass.size.x, pass.size.y, pass.samples);
    if (!std::isnan(milliseconds)) std::printf("; %.1f ms per pass after the first", milliseconds);
    if (!std::isnan(estimate.relMse))
        std::printf("; estimated relMSE %.3e (band %.1e .. %.1e)", estimate.relMse, estimate.low, estimate.high);
    std::printf(")\n");
    std::fflush(stdout);
}

// Where V writes the view: --view, else ripple-view.json in the working folder.
std::filesystem::path viewFileOf(const Options& options) {
    return options.view.empty() ? std::filesystem::path("ripple-view.json") : std::filesystem::path(options.view);
}

void saveView(const std::filesystem::path& file, const CameraView& view, const ViewerUiState& ui, glm::uvec2 size,
              const SceneEdits& edits) {
    ViewState state;
    state.camera = view;
    state.renderer = "default";
    state.pixelSamples = ui.settings.pixelSamples;
    state.maxPathLength = ui.settings.maxPathLength;
    state.ambientRadiance = ui.settings.ambientRadiance;
    state.background = ui.settings.background;
    state.size = size;
    if (!ui.traversal.empty()) state.traversal = ui.traversal;
    state.lights = edits.lights;
    state.volumes = edits.volumes;
    state.isosurfaces = edits.isosurfaces;
    try {
        writeViewState(file, state);
        std::printf("wrote view %s (ripple-render --view %s renders it)\n", file.c_str(), file.c_str());
        std::fflush(stdout);
    } catch (const std::exception& e) {  // the session goes on
        std::fprintf(stderr, "[ripple-view] ERROR: %s\n", e.what());
    }
}

// This rank's share of the scene (all of it with one rank); lights on rank 0 alone, as ripple-render places
// them (the device gathers every rank's lights). `edits` (rank 0's) lists what the scene panels edit.
AnariWorld buildScene(const Options& options, const std::optional<GltfScene>& gltf, const std::optional<FieldPlan>& field,
                      const mpi::Communicator& ranks, Session& s, const std::vector<ANARILight>& extraLights,
                      SceneEdits& edits) {
    if (field) return buildPlannedField(s.device, *field, extraLights, &edits);
    if (!gltf) return buildDemoScene(s.device, options.demo.empty() ? "default" : options.demo, extraLights, &edits);
    const GltfScene share = partitionScene(*gltf, uint32_t(ranks.rank()), uint32_t(ranks.size()),
                                           parsePartitionKind(options.partition));
    return buildAnariWorld(s.device, share, ranks.rank() == 0, extraLights, &edits);
}

// Ranks other than 0 under mpirun: the same scene share and device as rank 0, no window; each pass as rank 0
// orders it, until it says the viewer closed.
int followRankZero(const Options& options, const mpi::Communicator& ranks, Session& s) {
    if (!shareStart(ranks, false)) return 1;  // rank 0's answer; it said why
    // The same collectives in the same order as rank 0: the device, the field's value range, the bounds.
    StatusLog log{"ripple-view", options.quiet, 0};
    openAnariDevice(options.library, log, s);
    const std::optional<FieldPlan> field = planField(options.field, ranks, false, "ripple-view", true);
    const std::optional<GltfScene> gltf = options.scene.empty() ? std::nullopt : std::optional(loadGltf(options.scene));
    SceneEdits edits(s.device);  // this rank's slab of the volumes rank 0's panel edits
    const AnariWorld scene = buildScene(options, gltf, field, ranks, s, {}, edits);
    s.objects.push_back(scene.world);
    worldBounds(s.device, scene);  // collective: rank 0 frames the view on the union of the ranks' bounds
    const PassOrder start = sharePassOrder(ranks, {});
    if (start.quit) return 0;
    if (!start.changes.view || !start.changes.settings || !start.changes.size || !start.changes.reducedScale)
        throw std::runtime_error("rank 0's first order lacks the view, settings or size");
    ProgressiveFrames frames(s, scene, *start.changes.view, *start.changes.size, *start.changes.settings,
                             *start.changes.reducedScale, false);
    for (PassOrder order = sharePassOrder(ranks, {}); !order.quit; order = sharePassOrder(ranks, {})) {
        if (!order.fieldEdits.empty())
            frames.editScene([&edits, requests = decodeFieldEdits(order.fieldEdits, edits)] { edits.commit(requests); });
        frames.apply(order.changes);
        // Rank 0 decided the pass is due: no sample limit here (none is in flight, so it starts).
        if (!frames.startPass(order.moving, 0))
            throw std::runtime_error("rank " + std::to_string(ranks.rank()) + " cannot start the pass rank 0 started");
        frames.poll(true);
    }
    return log.errors > 0 ? 1 : 0;
}

int run(const Options& options, const mpi::Communicator& ranks, Session& s) {
    // Everything that can fail without a window is checked first; under mpirun the other ranks wait for its
    // outcome (and end with rank 0 when it fails).
    std::optional<ViewerWindow> windowHolder;
    std::optional<ViewState> savedView;
    std::optional<GltfScene> gltf;
    std::optional<LinearImage> environment;
    glm::uvec2 size{0, 0};
    const bool headless = !options.screenshot.empty();
    const std::string demo =
        options.scene.empty() && options.demo.empty() && options.field.volume.empty() ? "default" : options.demo;
    try {
        if (!options.view.empty() && std::filesystem::exists(options.view)) {
            if (options.camera) throw std::runtime_error("give one of --camera and an existing --view file");
            savedView = readViewState(options.view);
        }
        size = savedView && savedView->size && !options.sizeGiven ? *savedView->size : parseImageSize(options.size);
        if (!options.scene.empty() && !options.demo.empty())
            throw std::runtime_error("give either a scene file or --demo, not both");
        if (!options.field.volume.empty() && (!options.scene.empty() || !options.demo.empty()))
            throw std::runtime_error("give one of a scene file, --demo or --volume");
        if (ranks.distributed() && options.scene.empty() && options.field.volume.empty())
            throw std::runtime_error("the demo scenes are not split over ranks: give a glTF file or --volume under mpirun");
        if (!demo.empty()) checkDemoSceneName(demo);
        parsePartitionKind(options.partition);
        checkVolumeOptions(options.field);  // the file itself is read on every rank after the start
        if (headless) {
            outputFormatOf(options.screenshot, "--screenshot");
            checkOutputWritable(options.screenshot, "--screenshot");
        }
        if (!options.scene.empty()) {
            gltf = loadGltf(options.scene);
            if (!options.quiet)
                for (const std::string& warning : gltf->warnings) std::fprintf(stderr, "[ripple-view] WARNING: %s\n", warning.c_str());
            if (options.camera && *options.camera >= int(gltf->cameras.size()))
                throw std::runtime_error("--camera " + std::to_string(*options.camera) + ": the scene has " +
                                         std::to_string(gltf->cameras.size()) + " cameras");
        }
        environment = readEnvironment(options.environment);
        const std::string title = !options.field.volume.empty() ? "ripple-view: " + options.field.volume
                                  : options.scene.empty()        ? "ripple-view: demo " + demo
                                                                 : "ripple-view: " + options.scene;
        windowHolder.emplace(size, title);
    } catch (const std::exception& e) {
        if (ranks.distributed()) shareStart(ranks, false);  // the other ranks end without a word
        std::fprintf(stderr, "[ripple-view] ERROR: %s\n", e.what());
        return 1;
    }
    if (ranks.distributed()) shareStart(ranks, true);
    ViewerWindow& window = *windowHolder;

    StatusLog log{"ripple-view", options.quiet, 0};
    openAnariDevice(options.library, log, s);
    SceneEdits edits(s.device);  // what the Lights and Volumes panels edit
    std::vector<ANARILight> extraLights;
    if (environment) {
        extraLights.push_back(newEnvironmentLight(s.device, *environment, options.environment.intensity,
                                                  options.environment.rotationDegrees, &edits));
        s.objects.push_back(extraLights.back());
    }
    // Collective under mpirun (the colour map spans every rank's values); a bad file ends every rank.
    const std::optional<FieldPlan> field = planField(options.field, ranks, true, "ripple-view", options.quiet);
    AnariWorld scene = buildScene(options, gltf, field, ranks, s, extraLights, edits);
    if (environment) scene.ambientRadiance = 0.0f;  // the environment replaces the scene's ambient fill
    s.objects.push_back(scene.world);
    const auto [lo, hi] = worldBounds(s.device, scene);

    ViewerUiState ui;
    ui.onlyGatheredChannels = ranks.distributed();
    // The traversal back-end, where the device lists the choices (one rank: every rank would have to switch).
    if (!ranks.distributed())
        if (const auto* values = static_cast<const char* const*>(anariGetParameterInfo(
                s.device, ANARI_DEVICE, "default", "traversal", ANARI_STRING, "value", ANARI_STRING_LIST)))
            for (const char* const* v = values; *v; ++v) ui.traversals.emplace_back(*v);
    SceneEditRequests editsToCommit;  // panel edits not yet handed to the frames (they wait for a pass to end)
    if (savedView) {
        // The file's panel values, committed before the first pass (and sent to the other ranks with it).
        editsToCommit = applyViewEdits(*savedView, edits, true, options.view);
        if (savedView->traversal) {
            if (std::find(ui.traversals.begin(), ui.traversals.end(), *savedView->traversal) != ui.traversals.end()) {
                ui.traversal = *savedView->traversal;
                anariSetParameter(s.device, s.device, "traversal", ANARI_STRING, ui.traversal.c_str());
                anariCommitParameters(s.device, s.device);
            } else if (!options.quiet) {
                std::fprintf(stderr, "[ripple-view] WARNING: %s: traversal \"%s\" %s; the device's default stays\n",
                             options.view.c_str(), savedView->traversal->c_str(),
                             ranks.distributed() ? "is not chosen under mpirun (every rank would have to switch)"
                                                 : "is not one this device offers");
            }
        }
    }
    ui.settings.pixelSamples = options.samplesPerPass;
    ui.settings.maxPathLength = options.maxPathLength;
    ui.settings.background = scene.background;
    ui.settings.ambientRadiance = scene.ambientRadiance;
    ui.settings.quickLookWhileMoving = !options.noQuickLook;
    if (savedView) {  // the file's settings, where the command line does not give them
        if (savedView->pixelSamples && !options.samplesGiven) ui.settings.pixelSamples = *savedView->pixelSamples;
        if (savedView->maxPathLength && !options.pathLengthGiven) ui.settings.maxPathLength = *savedView->maxPathLength;
        if (savedView->ambientRadiance) ui.settings.ambientRadiance = *savedView->ambientRadiance;
        if (savedView->background) ui.settings.background = *savedView->background;
    }
    ui.selectedCamera = options.camera.value_or(scene.cameras.empty() ? -1 : 0);
    if (ui.selectedCamera >= int(scene.cameras.size()))
        throw std::runtime_error("--camera " + std::to_string(ui.selectedCamera) + ": the scene has " +
                                 std::to_string(scene.cameras.size()) + " cameras");
    // The render follows the window's drawable, except for a screenshot, which has exactly --size.
    glm::uvec2 renderSize = headless ? size : glm::max(window.framebufferSize(), glm::uvec2(1));
    const auto aspect = [&] { return float(renderSize.x) / float(renderSize.y); };
    OrbitCamera camera;
    camera.reset(savedView                ? savedView->camera
                 : ui.selectedCamera >= 0 ? scene.cameras[size_t(ui.selectedCamera)]
                                          : frameBounds(lo, hi, aspect()),
                 lo, hi);
    const uint32_t reducedScale = 2;
    // The other ranks make their frames from the same view, size and settings.
    sharePassOrder(ranks, {false, false, {camera.view(), ui.settings, renderSize, reducedScale}, {}});
    ProgressiveFrames frames(s, scene, camera.view(), renderSize, ui.settings, reducedScale);
    ui.quickLookAvailable = frames.hasQuickLook();

    using Clock = std::chrono::steady_clock;
    Clock::time_point lastChange = Clock::now() - std::chrono::seconds(1);
    Clock::time_point lastLoop = Clock::now();
    uint32_t fullPasses = 0;
    double laterPassMilliseconds = 0.0;  // full-size passes after the first
    std::optional<std::filesystem::path> screenshotRequest;
    while (!window.closing()) {
        window.beginFrame(frames.busy() ? 0.008 : 0.05);
        const Clock::time_point now = Clock::now();
        const float dt = std::min(std::chrono::duration<float>(now - lastLoop).count(), 0.1f);
        lastLoop = now;
        bool viewChanged = false;
        if (!headless) {
            const ImGuiIO& io = ImGui::GetIO();
            const float height = std::max(io.DisplaySize.y, 1.0f);
            if (!io.WantCaptureMouse) {
                const float dx = io.MouseDelta.x / height, dy = io.MouseDelta.y / height;
                if (ImGui::IsMouseDown(0) && (dx != 0.0f || dy != 0.0f)) {
                    camera.orbit(dx * 3.14159265f, dy * 3.14159265f);
                    viewChanged = true;
                } else if ((ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2)) && (dx != 0.0f || dy != 0.0f)) {
                    camera.pan(dx, dy);
                    viewChanged = true;
                }
                if (io.MouseWheel != 0.0f) {
                    camera.zoom(io.MouseWheel);
                    viewChanged = true;
                }
            }
            bool frameScene = false;
            if (!io.WantCaptureKeyboard) {
                const float speed = dt * (ImGui::IsKeyDown(GLFW_KEY_LEFT_SHIFT) ? 1.0f : 0.25f);
                const auto axis = [](int plus, int minus) {
                    return (ImGui::IsKeyDown(plus) ? 1.0f : 0.0f) - (ImGui::IsKeyDown(minus) ? 1.0f : 0.0f);
                };
                const float forward = axis(GLFW_KEY_W, GLFW_KEY_S), right = axis(GLFW_KEY_D, GLFW_KEY_A),
                            up = axis(GLFW_KEY_E, GLFW_KEY_Q);
                if (forward != 0.0f || right != 0.0f || up != 0.0f) {
                    camera.fly(forward * speed, right * speed, up * speed);
                    viewChanged = true;
                }
                frameScene = ImGui::IsKeyPressed(GLFW_KEY_F, false);
                if (ImGui::IsKeyPressed(GLFW_KEY_P, false))
                    screenshotRequest = nextScreenshotName(ImGui::IsKeyDown(GLFW_KEY_LEFT_SHIFT) ||
                                                           ImGui::IsKeyDown(GLFW_KEY_RIGHT_SHIFT));
                if (ImGui::IsKeyPressed(GLFW_KEY_V, false)) saveView(viewFileOf(options), camera.view(), ui, renderSize, edits);
            }
            CameraView& view = camera.view();
            const PanelRequests requests = drawPanels(ui, view, scene.cameras, frames.latest(), frames.fullSamples(),
                                                      now - lastChange < std::chrono::duration<double>(kSettleSeconds),
                                                      frames.busy());
            if (requests.viewChanged) {
                camera.reset(view, lo, hi);
                viewChanged = true;
            }
            if (frameScene || requests.frameScene) {
                CameraView framed = frameBounds(lo, hi, aspect());
                if (!view.orthographic) framed.fovy = view.fovy;
                camera.reset(framed, lo, hi);
                ui.selectedCamera = -1;
                viewChanged = true;
            }
            if (const SceneEditRequests edited = drawScenePanels(edits); !edited.empty()) {
                editsToCommit.merge(edited);
                lastChange = now;  // redraw at reduced size while a slider moves
            }
            if (requests.settingsChanged) frames.setSettings(ui.settings);
            if (requests.traversalChanged)  // the device builds its scene and kernels anew for the next pass
                frames.editScene([device = s.device, traversal = ui.traversal] {
                    anariSetParameter(device, device, "traversal", ANARI_STRING, traversal.c_str());
                    anariCommitParameters(device, device);
                });
            if (requests.screenshot) screenshotRequest = nextScreenshotName(false);
            if (requests.screenshotExr) screenshotRequest = nextScreenshotName(true);
            if (requests.saveView) saveView(viewFileOf(options), camera.view(), ui, renderSize, edits);
            if (const glm::uvec2 fb = window.framebufferSize(); fb.x > 0 && fb.y > 0 && fb != renderSize) {
                renderSize = fb;
                frames.setSize(renderSize);
                viewChanged = true;
            }
        }
        if (viewChanged) {
            frames.setView(camera.view());
            lastChange = now;
        }
        if (frames.poll()) {
            const PassResult& pass = frames.latest();
            window.showImage(pass);
            if (!pass.reduced) {
                if (++fullPasses > 1) laterPassMilliseconds += pass.milliseconds;
                const double meanMilliseconds =
                    fullPasses > 1 ? laterPassMilliseconds / double(fullPasses - 1) : std::nan("");
                if (screenshotRequest) {
                    writeScreenshot(*screenshotRequest, pass, pass.reduced ? ErrorEstimate{} : frames.estimateNow(), meanMilliseconds);
                    screenshotRequest.reset();
                }
                if (headless && fullPasses >= options.frames) {
                    writeScreenshot(options.screenshot, pass, pass.reduced ? ErrorEstimate{} : frames.estimateNow(), meanMilliseconds);
                    window.endFrame();
                    break;
                }
            }
        }
        frames.setReducedScale(ui.reduceWhileMoving ? uint32_t(ui.movingDivisor) : 1);
        const bool moving = !headless &&
                            now - lastChange < std::chrono::duration<double>(kSettleSeconds);
        std::vector<uint8_t> fieldEdits;  // the other ranks' share of the edits (their volume slabs)
        if (!editsToCommit.empty() && !frames.busy()) {
            frames.editScene([&edits, requests = editsToCommit] { edits.commit(requests); });
            // Lights need nothing sent: rank 0 alone holds them (the device restarts every rank's frame).
            if (ranks.distributed() && (!editsToCommit.volumes.empty() || !editsToCommit.isosurfaces.empty()))
                fieldEdits = encodeFieldEdits(edits, editsToCommit);
            editsToCommit = {};
        }
        const uint32_t maxSamples = headless ? 0 : ui.maxSamples;
        if (ranks.distributed() && frames.passDue(moving, maxSamples))
            sharePassOrder(ranks, {false, moving, frames.pending(), std::move(fieldEdits)});
        frames.startPass(moving, maxSamples);
        window.endFrame();
    }
    frames.poll(true);
    sharePassOrder(ranks, {true, false, {}, {}});  // the other ranks end
    if (log.errors > 0) {
        std::fprintf(stderr, "[ripple-view] ERROR: the device reported %d error(s)\n", log.errors);
        return 1;
    }
    return 0;
}

}  // namespace
}  // namespace ripple::apps

int main(int argc, char** argv) {
    ripple::mpi::Runtime runtime(&argc, &argv);
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();  // collective: before anything can fail
    ripple::apps::Options options;
    CLI::App app{"ripple-view: view a glTF 2.0 file, a volume file or a built-in demo scene interactively through an "
                 "ANARI library.\n"
                 "Mouse: left drag orbits, right or middle drag pans, the wheel zooms. Keys: W/A/S/D/Q/E fly (shift: "
                 "faster), F frames the scene, P writes a screenshot (ripple-view-NNN.png; shift+P: .exr, linear HDR), V saves the view (camera, panel values, "
                 "settings, size) for ripple-render --view. Panels: Renderer, Camera, Lights, Volumes.\n"
                 "Under mpirun every rank holds its share of a file (--partition, or --volume slabs); rank 0 shows the "
                 "window."};
    app.add_option("scene", options.scene, "glTF 2.0 file (.gltf or .glb); without one a demo scene is shown");
    std::string demoNames;
    for (const std::string& n : ripple::apps::demoSceneNames()) demoNames += (demoNames.empty() ? "" : ", ") + n;
    app.add_option("--demo", options.demo, "built-in scene: " + demoNames + " (default: default)");
    app.add_option("--library", options.library, "ANARI library name (loads libanari_library_NAME.so)")->capture_default_str();
    app.add_option("--size", options.size, "window (and image) size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--spp", options.samplesPerPass, "samples per pixel in each pass")
        ->check(CLI::Range(1, 64))->capture_default_str();
    app.add_option("--max-path-length", options.maxPathLength, "surface interactions per path")
        ->check(CLI::Range(1, 1024))->capture_default_str();
    app.add_option("--camera", options.camera, "scene camera index; -1 frames the scene bounds (default: camera 0 if any)")
        ->check(CLI::Range(-1, 1 << 20));
    CLI::Option* screenshot = app.add_option("--screenshot", options.screenshot,
                   "render --frames full-size passes, write the image (.png, .jpg, .pfm, .exr) and exit");
    app.add_option("--frames", options.frames, "passes before --screenshot is written")
        ->check(CLI::Range(1u, 1000000u))->needs(screenshot)->capture_default_str();
    app.add_flag("--no-quick-look", options.noQuickLook,
                 "path-trace while the view moves too (by default moving passes use the device's 'eyeLight' "
                 "renderer, a quick look lit from the eye, where the device has one)");
    app.add_option("--view", options.view,
                   "view-state file: read at start when it exists (camera, settings, size where the command line "
                   "does not set them, and the Lights and Volumes panels' values); V writes it (default: "
                   "ripple-view.json)");
    ripple::apps::addEnvironmentOptions(app, options.environment);
    ripple::apps::addVolumeOptions(app, options.field);
    app.add_option("--partition", options.partition,
                   "under mpirun, each rank imports: round-robin (whole mesh instances dealt in turn) or spatial "
                   "(the triangles of one k-d region per rank)")
        ->capture_default_str();
    app.add_flag("-q,--quiet", options.quiet, "no warnings");
    CLI11_PARSE(app, argc, argv);
    options.sizeGiven = app.count("--size") > 0;
    options.samplesGiven = app.count("--spp") > 0;
    options.pathLengthGiven = app.count("--max-path-length") > 0;

    ripple::apps::Session session;  // outlives the viewer's objects, which are released first
    try {
        return ranks.rank() == 0 ? ripple::apps::run(options, ranks, session)
                                 : ripple::apps::followRankZero(options, ranks, session);
    } catch (const std::exception& e) {
        // Under mpirun the other ranks may be inside a collective this rank never enters: end them all.
        if (ranks.distributed()) ranks.abort("[ripple-view] ERROR (rank " + std::to_string(ranks.rank()) + "): " + e.what());
        std::fprintf(stderr, "[ripple-view] ERROR: %s\n", e.what());
        return 1;
    }
}
