// ripple-render: renders a glTF file, a volume file (raw or NRRD) or a built-in demo scene to a PNG (or JPEG,
// PFM) through any ANARI library, using only standard ANARI objects and parameters. Frames accumulate samples
// batch by batch; after each the float color channel feeds a no-reference error estimate (Convergence.h),
// reported as it falls.
#include "apps/ripple-render/Render.h"

#include "apps/ripple-render/Convergence.h"
#include "apps/ripple-render/ErrorPlot.h"
#include "apps/ripple-render/Progress.h"
#include "apps/ripple-render/RankAgreement.h"
#include "apps/ripple-render/RankStats.h"
#include "apps/ripple-render/TimeBudget.h"
#include "apps/scene/AnariParams.h"
#include "apps/scene/AnariScene.h"
#include "apps/scene/AnariSession.h"
#include "apps/scene/DemoScene.h"
#include "apps/scene/EnvironmentOptions.h"
#include "apps/scene/ImageSize.h"
#include "apps/scene/SceneEdits.h"
#include "apps/scene/ScenePartition.h"
#include "apps/scene/ViewState.h"
#include "apps/scene/VolumeOptions.h"
#include "io/FileWrite.h"
#include "io/gltf/GltfScene.h"
#include "io/image/ImageIO.h"
#include "io/image/OutputImage.h"
#include "io/volume/VolumeFile.h"
#include "metrics/HeatMap.h"
#include "mpi/Communicator.h"
#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

namespace ripple::apps {
namespace {

// Samples per frame: the smallest divisor of spp that needs at most 16 frames, so the progress line moves
// and every frame carries the same count (changing pixelSamples may restart a device's accumulation).
uint32_t samplesPerFrame(uint32_t spp) {
    for (uint32_t batch = 1; batch < spp; ++batch)
        if (spp % batch == 0 && spp / batch <= 16) return batch;
    return spp;
}

// Maps the color channel (FLOAT32_VEC4) after frame number `frames` (from 1) of `batch` samples and adds
// it to the estimator. A device that reports `numSamples` says how many samples the mapped average holds;
// one that does not is taken to accumulate when it lists ANARI_KHR_FRAME_ACCUMULATION.
void addFrameToEstimator(ANARIDevice device, ANARIFrame frame, glm::uvec2 size, uint32_t frames, uint32_t batch,
                         bool accumulationExtension, HalfBufferEstimator& estimator) {
    uint32_t width = 0, height = 0;
    ANARIDataType mappedType = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(device, frame, "channel.color", &width, &height, &mappedType);
    if (!pixels || width != size.x || height != size.y || mappedType != ANARI_FLOAT32_VEC4) {
        if (pixels) anariUnmapFrame(device, frame, "channel.color");
        throw std::runtime_error("the device returned no " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                                 " FLOAT32_VEC4 color channel");
    }
    const float* mean = static_cast<const float*>(pixels);
    uint32_t samples = 0;
    try {
        if (anariGetProperty(device, frame, "numSamples", ANARI_UINT32, &samples, sizeof samples, ANARI_WAIT)) {
            if (samples > estimator.samples()) estimator.addAccumulatedFrame(mean, samples);
            else estimator.addBatchFrame(mean, batch);  // the device started afresh: this frame alone
        } else if (accumulationExtension) {
            estimator.addAccumulatedFrame(mean, frames * batch);
        } else {
            estimator.addBatchFrame(mean, batch);
        }
    } catch (...) {
        anariUnmapFrame(device, frame, "channel.color");
        throw;
    }
    anariUnmapFrame(device, frame, "channel.color");
}

// What the options ask for, checked before any library is loaded so that bad input fails fast.
struct RenderPlan {
    PartitionKind partition = PartitionKind::RoundRobin;
    bool root = true;
    glm::uvec2 size{0, 0};
    OutputFormat format = OutputFormat::Png;
    std::filesystem::path reportFile, plotFile;
    OutputFormat errorMapFormat = OutputFormat::Pfm;
    std::optional<LinearImage> reference;
    std::string demo;                   // the demo scene, or empty for a file
    std::optional<GltfScene> gltf;
    std::optional<LinearImage> environment;  // --environment's image
    std::optional<FieldPlan> field;     // --volume
    bool depth = false, normal = false, albedo = false;  // --channels
};

// The frame channels beside the colour that --channels writes as EXR layers, mapped after the last frame
// (rows bottom first): depth 1 float per pixel, normal and albedo 3.
struct ExtraChannels {
    std::vector<float> depth, normal, albedo;
};

// The host memory ripple-render's own buffers for a w x h image take on rank 0: the estimator's sums (RGBA doubles:
// the previous total and the two halves), one batch's sum while a frame is added, the mean image written
// at the end, and the reference when given (RGB floats).
uint64_t appBytes(glm::uvec2 size, bool reference) {
    const uint64_t pixels = uint64_t(size.x) * size.y;  // two 32-bit factors: no overflow
    return pixels * (3 * 32 + 32 + 16 + (reference ? 12 : 0));
}

// MemAvailable of /proc/meminfo, capped by RIPPLE_MEMORY_LIMIT (bytes) as the device caps it.
uint64_t availableHostBytes() {
    uint64_t available = std::numeric_limits<uint64_t>::max();
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        uint64_t kib = 0;
        if (key == "MemAvailable:" && meminfo >> kib) {
            available = kib * 1024;
            break;
        }
        meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    if (const char* limit = std::getenv("RIPPLE_MEMORY_LIMIT"); limit && *limit)
        available = std::min<uint64_t>(available, std::strtoull(limit, nullptr, 10));
    return available;
}

RenderPlan checkOptions(const Options& options, const mpi::Communicator& ranks) {
    RenderPlan plan;
    plan.partition = parsePartitionKind(options.partition);
    plan.root = ranks.rank() == 0;
    plan.size = parseImageSize(options.size);
    plan.format = outputFormatOf(options.output);
    for (const std::string& channel : options.channels) {
        if (channel == "depth") plan.depth = true;
        else if (channel == "normal") plan.normal = true;
        else if (channel == "albedo") plan.albedo = true;
        else throw std::runtime_error("--channels: unknown channel '" + channel + "' (known: depth, normal, albedo)");
    }
    if ((plan.normal || plan.albedo) && ranks.distributed())
        throw std::runtime_error("--channels normal and albedo are not gathered across ranks under mpirun (depth is)");
    if ((!options.channels.empty() || options.exrHalf) && plan.format != OutputFormat::Exr)
        throw std::runtime_error(std::string(options.exrHalf ? "--exr-half" : "--channels") + " needs an .exr output (-o)");
    plan.reportFile = options.report;
    plan.plotFile = std::filesystem::path(options.report).replace_extension(".png");
    if (!options.report.empty()) {
        if (plan.reportFile == plan.plotFile)
            throw std::runtime_error("--report " + options.report + ": give a .csv file (the plot goes beside it as .png)");
        if (plan.reportFile.has_parent_path() && !std::filesystem::is_directory(plan.reportFile.parent_path()))
            throw std::runtime_error("--report " + options.report + ": no such folder");
        if (std::filesystem::weakly_canonical(plan.plotFile) == std::filesystem::weakly_canonical(options.output))
            throw std::runtime_error("--report " + options.report + ": its plot " + plan.plotFile.string() +
                                     " would overwrite the output image");
        if (options.sppGiven && options.spp < 2)
            throw std::runtime_error("--report with --spp 1: the error estimate needs 2 samples or more");
    }
    if (!options.errorMap.empty()) {
        plan.errorMapFormat = outputFormatOf(options.errorMap, "--error-map");
        if (plan.errorMapFormat == OutputFormat::Jpeg)
            throw std::runtime_error("--error-map " + options.errorMap + ": give a .png (heat map), .pfm or .exr file");
        if (std::filesystem::weakly_canonical(options.errorMap) == std::filesystem::weakly_canonical(options.output))
            throw std::runtime_error("--error-map " + options.errorMap + " would overwrite the output image");
        if (options.spp < 2)
            throw std::runtime_error("--error-map with --spp 1: the error estimate needs 2 samples or more");
    }
    // Only rank 0 writes: it finds out now, not after the render, that it cannot.
    if (plan.root) checkOutputWritable(options.output);
    if (plan.root && !options.errorMap.empty()) checkOutputWritable(options.errorMap, "--error-map");
    if (plan.root && !options.report.empty()) {
        checkWritable(plan.reportFile, "the report");
        checkWritable(plan.plotFile, "the report's plot");
    }
    if (const uint64_t needed = appBytes(plan.size, !options.reference.empty()), available = availableHostBytes();
        plan.root && needed > available)
        throw std::runtime_error("--size " + std::to_string(plan.size.x) + "x" + std::to_string(plan.size.y) +
                                 ": ripple-render's image buffers need " + std::to_string(needed) + " bytes but only " +
                                 std::to_string(available) + " are available; use a smaller size");
    if (!options.reference.empty()) {
        plan.reference = readLinearImage(options.reference);
        if (plan.reference->width != plan.size.x || plan.reference->height != plan.size.y)
            throw std::runtime_error("--reference " + options.reference + " is " + std::to_string(plan.reference->width) +
                                     "x" + std::to_string(plan.reference->height) + " but the render is " + options.size);
    }
    if (!options.scene.empty() && !options.demo.empty())
        throw std::runtime_error("give either a scene file or --demo, not both");
    if (!options.field.volume.empty() && (!options.scene.empty() || !options.demo.empty()))
        throw std::runtime_error("give one of a scene file, --demo or --volume");
    plan.field = planField(options.field, ranks, plan.root, "ripple-render", options.quiet);
    plan.demo = options.scene.empty() && options.demo.empty() && options.field.volume.empty() ? "default" : options.demo;
    if (!plan.demo.empty()) checkDemoSceneName(plan.demo);
    if (ranks.distributed() && !plan.demo.empty())
        throw std::runtime_error("the demo scenes are not split over ranks: give a glTF file or --volume under mpirun");

    // Every rank reads it and makes the light, so that all build the same scene settings; only rank 0
    // places lights in its world (the device gathers them).
    plan.environment = readEnvironment(options.environment);

    // The file is read before any library is loaded, so a bad file fails fast.
    if (!options.scene.empty()) {
        plan.gltf = loadGltf(options.scene, {.resourceRoot = options.resourceRoot});
        if (!options.quiet && plan.root)
            for (const std::string& warning : plan.gltf->warnings)
                std::fprintf(stderr, "[ripple-render] WARNING: %s\n", warning.c_str());
    }
    return plan;
}

void openDevice(const Options& options, StatusLog& log, Session& s) {
    openAnariDevice(options.library, log, s);
    if (!options.traversal.empty())
        anariSetParameter(s.device, s.device, "traversal", ANARI_STRING, options.traversal.c_str());
    if (!options.exchange.empty())
        anariSetParameter(s.device, s.device, "rayExchange", ANARI_STRING, options.exchange.c_str());
    if (!options.traversal.empty() || !options.exchange.empty()) anariCommitParameters(s.device, s.device);
}

// The scene on the device: under mpirun each rank imports only its share of the file, so that no rank holds
// the whole scene; the lights become ANARI lights on rank 0 alone (the device gathers every rank's lights).
AnariWorld buildScene(const Options& options, RenderPlan& plan, const mpi::Communicator& ranks, Session& s,
                      RankStats& stats) {
    std::optional<GltfScene>& gltf = plan.gltf;
    if (gltf && ranks.distributed() && plan.partition == PartitionKind::RoundRobin &&
        gltf->instances.size() < size_t(ranks.size()) && plan.root)
        std::fprintf(stderr, "[ripple-render] WARNING: %zu mesh instance(s) for %d ranks: some ranks hold nothing and one "
                     "holds whole meshes; --partition spatial splits meshes\n", gltf->instances.size(), ranks.size());
    if (gltf) gltf = partitionScene(*gltf, uint32_t(ranks.rank()), uint32_t(ranks.size()), plan.partition);
    stats.triangles = gltf ? gltf->trianglesDrawn() : 0;
    // The environment is a light like the scene's, placed on rank 0 alone.
    std::vector<ANARILight> extraLights;
    SceneEdits edits(s.device);  // what a --view file's panel values apply to
    if (plan.environment) {
        extraLights.push_back(newEnvironmentLight(s.device, *plan.environment, options.environment.intensity,
                                                  options.environment.rotationDegrees, &edits));
        s.objects.push_back(extraLights.back());
    }
    AnariWorld scene = plan.field ? buildPlannedField(s.device, *plan.field, extraLights, &edits)
                       : gltf     ? buildAnariWorld(s.device, *gltf, plan.root, extraLights, &edits)
                                  : buildDemoScene(s.device, plan.demo, extraLights, &edits);
    if (options.viewState) edits.commit(applyViewEdits(*options.viewState, edits, plan.root, options.view));
    if (plan.environment) scene.ambientRadiance = 0.0f;  // the environment replaces the scene's ambient fill
    s.objects.push_back(scene.world);
    return scene;
}

// The camera: the scene's (--camera), or one framing the bounds as the device computed them (the scene's
// own where the device does not answer).
ANARICamera makeCamera(const Options& options, const AnariWorld& scene, glm::uvec2 size, Session& s) {
    const auto [lo, hi] = worldBounds(s.device, scene);
    const float aspect = float(size.x) / float(size.y);
    CameraView view;
    const int cameraIndex = options.camera.value_or(scene.cameras.empty() ? -1 : 0);
    if (options.viewState) {
        view = options.viewState->camera;
    } else if (cameraIndex >= 0) {
        if (size_t(cameraIndex) >= scene.cameras.size())
            throw std::runtime_error("--camera " + std::to_string(cameraIndex) + ": the scene has " +
                                     std::to_string(scene.cameras.size()) + " cameras");
        view = scene.cameras[size_t(cameraIndex)];
    } else {
        view = frameBounds(lo, hi, aspect);
    }
    ANARICamera camera = newAnariCamera(s.device, view, aspect);
    s.objects.push_back(camera);
    return camera;
}

struct FrameSetup {
    ANARIFrame frame = nullptr;
    uint32_t batch = 1;                 // samples per frame
    bool accumulationExtension = false;
};

FrameSetup makeFrame(const Options& options, const RenderPlan& plan, const AnariWorld& scene, ANARICamera camera,
                     glm::uvec2 size, Session& s) {
    FrameSetup setup;
    setup.batch = options.reporting() ? 1 : samplesPerFrame(options.spp);
    // The error map needs two frames at least (one per half-buffer).
    if (!options.errorMap.empty()) setup.batch = std::max(1u, std::min(setup.batch, options.spp / 2));
    if (const std::vector<std::string> renderers = deviceSubtypes(s.device, ANARI_RENDERER);
        !renderers.empty() && std::find(renderers.begin(), renderers.end(), options.renderer) == renderers.end()) {
        std::string known;
        for (const std::string& name : renderers) known += (known.empty() ? "" : ", ") + name;
        throw std::runtime_error("--renderer: the device has no renderer '" + options.renderer + "' (it has: " + known + ")");
    }
    ANARIRenderer renderer = anariNewRenderer(s.device, options.renderer.c_str());
    if (!renderer) throw std::runtime_error("the device has no '" + options.renderer + "' renderer");
    s.objects.push_back(renderer);
    anari::set(s.device, renderer, "pixelSamples", int32_t(setup.batch));
    anari::set(s.device, renderer, "maxPathLength", int32_t(options.maxPathLength));
    if (options.seed != 0) anari::set(s.device, renderer, "seed", options.seed);  // 0: the device's default
    anari::set(s.device, renderer, "background", options.viewState && options.viewState->background ? *options.viewState->background : scene.background);
    // eyeLight's ambient light is the light at the eye: the scene's suggestion (meant for path tracing lit
    // scenes, often 0) would darken it, so only an explicit --ambient sets it.
    if (options.renderer != "eyeLight" || options.ambient)
        anari::set(s.device, renderer, "ambientRadiance",
                   options.ambient.value_or(options.viewState && options.viewState->ambientRadiance
                                                       ? *options.viewState->ambientRadiance
                                                       : scene.ambientRadiance));
    anariCommitParameters(s.device, renderer);

    setup.frame = anariNewFrame(s.device);
    if (!setup.frame) throw std::runtime_error("the device created no frame");
    s.objects.push_back(setup.frame);
    const ANARIDataType colorType = ANARI_FLOAT32_VEC4;  // the estimate needs the linear average
    anari::set(s.device, setup.frame, "size", size);
    anariSetParameter(s.device, setup.frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    const ANARIDataType depthType = ANARI_FLOAT32, vectorType = ANARI_FLOAT32_VEC3;
    if (plan.depth) anariSetParameter(s.device, setup.frame, "channel.depth", ANARI_DATA_TYPE, &depthType);
    if (plan.normal) anariSetParameter(s.device, setup.frame, "channel.normal", ANARI_DATA_TYPE, &vectorType);
    if (plan.albedo) anariSetParameter(s.device, setup.frame, "channel.albedo", ANARI_DATA_TYPE, &vectorType);
    setup.accumulationExtension = deviceHasExtension(s.device, "ANARI_KHR_FRAME_ACCUMULATION");
    if (setup.accumulationExtension) anari::set(s.device, setup.frame, "accumulation", true);
    anari::setObject(s.device, setup.frame, "world", ANARI_WORLD, scene.world);
    anari::setObject(s.device, setup.frame, "renderer", ANARI_RENDERER, renderer);
    anari::setObject(s.device, setup.frame, "camera", ANARI_CAMERA, camera);
    anariCommitParameters(s.device, setup.frame);
    return setup;
}

// The start-up on its own line: loading the library, reading the scene, making its objects, and the first
// frame, in which the device builds the scene and creates its pipelines.
void reportStartUp(const TimeBudget& budget) {
    std::printf("start-up %.2f s (library and scene %.2f s, first frame with its pipelines %.2f s)\n",
                budget.startUpSeconds(), budget.firstFrameBegin(), budget.firstFrameSeconds());
    std::fflush(stdout);
}

// What the frames' rays did, summed over frames (and ranks) from the device's "ripple.*" frame properties;
// all 0 on devices without them.
struct TracingWork {
    uint64_t flaggedRays = 0;      // ran out of their step budget: treated as misses
    uint64_t realCollisions = 0;   // volumes: delta tracking
    uint64_t nullCollisions = 0;
    uint64_t ratioCollisions = 0;  // volumes: ratio tracking of shadow rays
    uint64_t parkedMarches = 0;    // volumes: marches resumed after spending a dispatch's step budget

    void addFrame(ANARIDevice device, ANARIFrame frame) {
        const std::pair<const char*, uint64_t*> counters[] = {{"ripple.flaggedRays", &flaggedRays},
                                                              {"ripple.realCollisions", &realCollisions},
                                                              {"ripple.nullCollisions", &nullCollisions},
                                                              {"ripple.ratioCollisions", &ratioCollisions},
                                                              {"ripple.parkedMarches", &parkedMarches}};
        for (const auto& [name, total] : counters) {
            uint64_t value = 0;
            if (anariGetProperty(device, frame, name, ANARI_UINT64, &value, sizeof value, ANARI_WAIT)) *total += value;
        }
    }
    void sumOverRanks(const mpi::Communicator& ranks) {
        for (uint64_t* total : {&flaggedRays, &realCollisions, &nullCollisions, &ratioCollisions, &parkedMarches})
            *total = ranks.sum(*total);
    }
};

struct RenderOutcome {
    HalfBufferEstimator estimator;
    std::vector<ConvergencePoint> series;
    uint32_t frames = 0;
    TracingWork work;
};

// Frames until a stop: --time, --target-error, whichever comes first (and --spp when given); with neither,
// --spp. The largest --spp bounds a target that is never reached. Only rank 0 holds the image
// (data-parallel ANARI): it decides when to stop, and tells the others. The first frame ends the start-up
// (the device builds the scene and its pipelines in it); `budget` times it and every frame after it.
RenderOutcome renderFrames(const Options& options, const RenderPlan& plan, const FrameSetup& setup,
                           const mpi::Communicator& ranks, Session& s, RankStats& stats, TimeBudget& budget) {
    // Only rank 0 holds the image, so only it needs the estimator's buffers.
    RenderOutcome out{HalfBufferEstimator(plan.root ? plan.size.x : 0, plan.root ? plan.size.y : 0), {}, 0, {}};
    std::optional<FlipReference> flipReference;  // the reference prepared for FLIP, at the first report point
    const bool stopOnSpp = options.sppGiven || (!options.seconds && !options.targetError);
    const uint32_t sppLimit = stopOnSpp ? options.spp : kMaxSpp;
    const bool printPoints = options.reporting() && !options.quiet && plan.root;
    Progress progress(options.spp, !options.reporting() && !options.quiet && plan.root);
    RenderClock clock;
    uint32_t nextReport = 2;  // the first spp with a batch in each half
    bool reportsRays = true;  // until the device says it has no such property (only Ripple has it)
    const ANARIFrame frame = setup.frame;
    for (bool stop = false; !stop;) {
        const double frameBegin = budget.elapsed();
        anariRenderFrame(s.device, frame);
        anariFrameReady(s.device, frame, ANARI_WAIT);
        ++out.frames;
        out.work.addFrame(s.device, frame);
        float raysPerSecond = 0.0f;
        if (reportsRays)
            reportsRays = anariGetProperty(s.device, frame, "ripple.raysPerSecond", ANARI_FLOAT32, &raysPerSecond,
                                           sizeof raysPerSecond, ANARI_WAIT);
        if (options.stats) {  // this rank's traffic in the frame just rendered
            uint64_t rays = 0, bytes = 0;
            anariGetProperty(s.device, frame, "ripple.raysSent", ANARI_UINT64, &rays, sizeof rays, ANARI_WAIT);
            anariGetProperty(s.device, frame, "ripple.bytesSent", ANARI_UINT64, &bytes, sizeof bytes, ANARI_WAIT);
            stats.raysSent += rays;
            stats.bytesSent += bytes;
            ++stats.frames;
            // GPU time per stage (Ripple's property), after the first frame: lavapipe compiles a kernel
            // the first time it runs, which would count as that stage's time.
            if (out.frames > 1) ++stats.stageFrames;
            for (size_t i = 0; out.frames > 1 && i < core::kStageCount; ++i) {
                const std::string name = std::string("ripple.stageMicroseconds.") + core::stageName(core::Stage(i));
                uint64_t microseconds = 0;
                if (anariGetProperty(s.device, frame, name.c_str(), ANARI_UINT64, &microseconds, sizeof microseconds, ANARI_WAIT))
                    stats.stageMicroseconds[i] += microseconds;
            }
        }
        if (plan.root)
            addFrameToEstimator(s.device, frame, plan.size, out.frames, setup.batch, setup.accumulationExtension,
                                out.estimator);
        budget.frameEnded(frameBegin, budget.elapsed());
        if (out.frames == 1 && plan.root && !options.quiet) reportStartUp(budget);
        if (plan.root) {
            const uint32_t spp = out.estimator.samples();
            progress.update(spp, reportsRays ? raysPerSecond : 0.0f);
            // The estimate costs a pass over the image (about 60 ms at 512x512 here): made only where
            // something uses it, and once. A plain render estimates once, at the end.
            const bool estimated = options.targetError || (options.reporting() && spp >= nextReport);
            const ErrorEstimate estimate = estimated ? out.estimator.estimate() : ErrorEstimate{};
            // --time stops before a frame predicted to end past the limit, counted from the process's start:
            // the run ends within it, at most one frame early; a start-up past it leaves the first frame
            // alone, and a frame far slower than the ones before overruns it. Under --time every frame is
            // one sample, the smallest batch, so the last cannot shrink to fit (nor should it change:
            // Ripple restarts its accumulation when pixelSamples changes): a frame that does not fit is
            // not started.
            stop = spp >= sppLimit || !budget.nextFrameFits(budget.elapsed()) ||
                   (options.targetError && spp >= kMinSamplesForTarget && estimate.relMse <= *options.targetError);
            if (options.reporting() && (spp >= nextReport || stop)) {
                clock.pause();  // metrics and printing are not render time
                ConvergencePoint point{clock.seconds(), spp, estimated ? estimate : out.estimator.estimate(), std::nullopt};
                if (plan.reference) {
                    if (!flipReference) flipReference.emplace(*plan.reference);
                    point.reference = compareToReference(out.estimator.meanImage(), *plan.reference, *flipReference);
                }
                if (printPoints) std::printf("%s\n", formatConvergencePoint(point).c_str());
                std::fflush(stdout);
                out.series.push_back(point);
                nextReport = nextReportSpp(spp);
                clock.resume();
            }
        }
        if (ranks.distributed()) stop = ranks.max(uint64_t(stop ? 1 : 0)) > 0;
    }
    progress.finish();
    return out;
}

// Each pixel's estimated relMSE: the values themselves in PFM/EXR (grey), or a PNG heat map of log10 of them
// from 1e-4 (black) to 1 (yellow). A render of one frame has no estimate: it says so instead.
void writeErrorMap(const std::string& file, OutputFormat format, glm::uvec2 size, const HalfBufferEstimator& estimator) {
    const std::vector<double> map = estimator.errorMap();
    if (map.empty()) {
        std::fprintf(stderr, "[ripple-render] warning: --error-map %s not written: one frame gives no estimate\n",
                     file.c_str());
        return;
    }
    if (format == OutputFormat::Png) {
        std::vector<float> heat(map.size());
        for (size_t i = 0; i < map.size(); ++i)
            heat[i] = map[i] > 0.0 ? float((std::log10(map[i]) + 4.0) / 4.0) : 0.0f;
        writeHeatMap(file, size.x, size.y, heat);
        return;
    }
    std::vector<float> rgba(map.size() * 4, 1.0f);  // bottom row first, as a frame maps
    for (uint32_t y = 0; y < size.y; ++y)
        for (uint32_t x = 0; x < size.x; ++x)
            for (size_t c = 0; c < 3; ++c)
                rgba[(size_t(size.y - 1 - y) * size.x + x) * 4 + c] = float(map[size_t(y) * size.x + x]);
    writeOutputImage(file, format, size.x, size.y, rgba.data());
}

// The channels --channels asked for, as the frame holds them after its last render (the first surface of the
// latest sample; depth +inf where nothing was hit).
ExtraChannels mapExtraChannels(const RenderPlan& plan, ANARIFrame frame, ANARIDevice device) {
    ExtraChannels extra;
    const auto map = [&](const char* name, ANARIDataType expected, size_t components, std::vector<float>& values) {
        uint32_t width = 0, height = 0;
        ANARIDataType type = ANARI_UNKNOWN;
        const void* pixels = anariMapFrame(device, frame, name, &width, &height, &type);
        const bool ok = pixels && width == plan.size.x && height == plan.size.y && type == expected;
        if (ok) {
            const auto* floats = static_cast<const float*>(pixels);
            values.assign(floats, floats + size_t(width) * height * components);
        }
        if (pixels) anariUnmapFrame(device, frame, name);
        if (!ok) throw std::runtime_error(std::string("--channels: the device returned no ") + name + " channel");
    };
    if (plan.depth) map("channel.depth", ANARI_FLOAT32, 1, extra.depth);
    if (plan.normal) map("channel.normal", ANARI_FLOAT32_VEC3, 3, extra.normal);
    if (plan.albedo) map("channel.albedo", ANARI_FLOAT32_VEC3, 3, extra.albedo);
    return extra;
}

// The EXR output with --channels or --exr-half: colour RGBA, then depth as Z, normal.X/Y/Z, albedo.R/G/B.
void writeExrLayers(const Options& options, const RenderPlan& plan, const std::vector<float>& rgba,
                    const ExtraChannels& extra) {
    const bool half = options.exrHalf;
    std::vector<ExrChannel> channels = {{"R", rgba.data(), 4, half}, {"G", rgba.data() + 1, 4, half},
                                        {"B", rgba.data() + 2, 4, half}, {"A", rgba.data() + 3, 4, half}};
    if (plan.depth) channels.push_back({"Z", extra.depth.data(), 1, false});  // depth keeps 32 bits
    for (int c = 0; plan.normal && c < 3; ++c)
        channels.push_back({std::string("normal.") + "XYZ"[c], extra.normal.data() + c, 3, half});
    for (int c = 0; plan.albedo && c < 3; ++c)
        channels.push_back({std::string("albedo.") + "RGB"[c], extra.albedo.data() + c, 3, half});
    writeExrChannelsBottomUp(options.output, plan.size.x, plan.size.y, std::move(channels));
}

void writeResults(const Options& options, const RenderPlan& plan, const RenderOutcome& out, const ExtraChannels& extra,
                  uint32_t batch, const TimeBudget& budget) {
    const std::vector<float> image = out.estimator.meanRgbaBottomUp();
    if (!options.channels.empty() || options.exrHalf) writeExrLayers(options, plan, image, extra);
    else writeOutputImage(options.output, plan.format, plan.size.x, plan.size.y, image.data());
    if (!options.report.empty()) {
        writeConvergenceCsv(plan.reportFile, out.series);
        const std::string sceneName = !options.field.volume.empty() ? std::filesystem::path(options.field.volume).filename().string()
                                      : options.scene.empty() ? "demo " + plan.demo
                                                              : std::filesystem::path(options.scene).filename().string();
        writeErrorPlot(plan.plotFile, out.series, sceneName + ", " + options.size + ": relMSE against render time");
    }
    if (!options.errorMap.empty()) writeErrorMap(options.errorMap, plan.errorMapFormat, plan.size, out.estimator);
    const ErrorEstimate finalEstimate = out.estimator.estimate();
    char estimateText[64] = "n/a (one frame)";
    if (!std::isnan(finalEstimate.relMse))
        std::snprintf(estimateText, sizeof estimateText, "%.3e (band %.1e .. %.1e)", finalEstimate.relMse,
                      finalEstimate.low, finalEstimate.high);
    // The whole run so far, start-up included (what --time bounds), then its parts.
    char timeText[160];
    if (out.frames > 1)
        std::snprintf(timeText, sizeof timeText, "%.2f s (start-up %.2f s, then frames of up to %.3f s)",
                      budget.elapsed(), budget.startUpSeconds(), budget.longestFrame());
    else
        std::snprintf(timeText, sizeof timeText, "%.2f s (start-up %.2f s with the only frame)", budget.elapsed(),
                      budget.startUpSeconds());
    std::printf("rendered %ux%u, %u spp (%u frames of %u) in %s, estimated relMSE %s -> %s\n", plan.size.x,
                plan.size.y, out.estimator.samples(), out.frames, batch, timeText, estimateText, options.output.c_str());
    if (budget.startUpExceeded())
        std::printf("time limit exceeded by start-up: --time %g s, start-up %.2f s; one frame of %u spp rendered\n",
                    *budget.limit(), budget.startUpSeconds(), batch);
    if (!options.report.empty()) std::printf("report: %s, plot: %s\n", plan.reportFile.c_str(), plan.plotFile.c_str());
    const TracingWork& work = out.work;
    if (work.realCollisions + work.nullCollisions + work.ratioCollisions > 0) {
        const double ratio = work.realCollisions > 0 ? double(work.nullCollisions) / double(work.realCollisions) : 0.0;
        std::printf("volumes: %llu real and %llu null collisions in free flight (null/real %.2f), %llu in ratio "
                    "tracking of shadow rays; %llu marches parked and resumed\n",
                    (unsigned long long)work.realCollisions, (unsigned long long)work.nullCollisions, ratio,
                    (unsigned long long)work.ratioCollisions, (unsigned long long)work.parkedMarches);
    }
    if (work.flaggedRays > 0)
        std::printf("warning: %llu rays ran out of their step budget and were treated as misses (the image is "
                    "biased there)\n", (unsigned long long)work.flaggedRays);
}

}  // namespace

int render(const Options& options, const mpi::Communicator& ranks, Session& s, TimeBudget& budget) {
    RenderPlan plan = checkOptions(options, ranks);
    StatusLog log{"ripple-render", options.quiet, 0};
    openDevice(options, log, s);
    RankStats stats;
    const AnariWorld scene = buildScene(options, plan, ranks, s, stats);
    const ANARICamera camera = makeCamera(options, scene, plan.size, s);
    const FrameSetup setup = makeFrame(options, plan, scene, camera, plan.size, s);
    RenderOutcome out = renderFrames(options, plan, setup, ranks, s, stats, budget);
    if (ranks.distributed()) out.work.sumOverRanks(ranks);
    if (options.stats) {
        anariGetProperty(s.device, setup.frame, "ripple.sceneBytes", ANARI_UINT64, &stats.sceneBytes,
                         sizeof stats.sceneBytes, ANARI_WAIT);
        printRankStats(ranks, stats);
    }
    if (!plan.root) return log.errors > 0 ? 1 : 0;
    const ExtraChannels extra = mapExtraChannels(plan, setup.frame, s.device);
    writeResults(options, plan, out, extra, setup.batch, budget);
    if (log.errors > 0) {
        std::fprintf(stderr, "[ripple-render] ERROR: the device reported %d error(s); the image may be wrong\n", log.errors);
        return 1;
    }
    return 0;
}

}  // namespace ripple::apps
