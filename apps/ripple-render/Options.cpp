// ripple-render's options (see Options.h).
#include "apps/ripple-render/Options.h"

#include "apps/scene/DemoScene.h"

#include <cstring>

namespace ripple::apps {

void addRenderOptions(CLI::App& app, Options& options) {
    app.add_option("scene", options.scene, "glTF 2.0 file (.gltf or .glb); without one a demo scene is rendered");
    std::string demoNames;
    for (const std::string& n : demoSceneNames()) demoNames += (demoNames.empty() ? "" : ", ") + n;
    app.add_option("--demo", options.demo, "built-in scene: " + demoNames + " (default: default)");
    app.add_option("-o,--output", options.output, "output image: .png or .jpg/.jpeg (8-bit sRGB), .pfm (linear float RGB) or .exr (linear float RGBA)")->capture_default_str();
    app.add_option("--size", options.size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--spp", options.spp, "samples per pixel (with --time or --target-error: a cap, when given)")
        ->check(CLI::Range(1u, kMaxSpp))->capture_default_str();
    app.add_option("--time", options.seconds,
                   "end the whole run, start-up (library, scene, first frame's pipelines) included, within this many "
                   "seconds: stop before a frame predicted to end past it; a start-up past it gets one frame of 1 spp")
        ->check(CLI::PositiveNumber);
    app.add_option("--target-error", options.targetError, "stop when the estimated relMSE falls to this")
        ->check(CLI::PositiveNumber);
    app.add_option("--reference", options.reference,
                   "converged image (PNG, PFM, EXR) of the same view: also report the true relMSE, PSNR, SSIM, FLIP");
    app.add_option("--report", options.report,
                   "write the convergence series to this CSV and its log-log plot beside it (.png)");
    app.add_option("--error-map", options.errorMap,
                   "write each pixel's estimated relMSE: .pfm or .exr (the values) or .png (a heat map of log10 from "
                   "-4, black, to 0, yellow)");
    app.add_option("--library", options.library, "ANARI library name (loads libanari_library_NAME.so)")->capture_default_str();
    app.add_option("--renderer", options.renderer,
                   "the ANARI renderer subtype: Ripple has default (the path tracer) and eyeLight (a quick look: "
                   "the first surfaces lit from the eye, no lights or bounces)")
        ->capture_default_str();
    app.add_option("--traversal", options.traversal,
                   "ray traversal back-end, the device parameter 'traversal': auto (ray queries where the device "
                   "has them), software or rayQuery (default: the device's, which RIPPLE_TRAVERSAL may set)")
        ->check(CLI::IsMember({"auto", "software", "rayQuery"}));
    app.add_option("--exchange", options.exchange,
                   "under mpirun, how rays cross ranks, the device parameter 'rayExchange': bounds (only to the "
                   "ranks whose world boxes a ray enters, nearest first; the default) or ring (every ray through "
                   "every rank)")
        ->check(CLI::IsMember({"bounds", "ring"}));
    app.add_option("--max-path-length", options.maxPathLength, "surface interactions per path")
        ->check(CLI::Range(1u, 1024u))->capture_default_str();
    app.add_option("--seed", options.seed,
                   "the renderer's random seed: images with different seeds share no samples (render a reference "
                   "with another seed than the image it judges)")
        ->capture_default_str();
    app.add_option("--camera", options.camera, "scene camera index; -1 frames the scene bounds (default: camera 0 if any)")
        ->check(CLI::Range(-1, 1 << 20));
    app.add_option("--channels", options.channels,
                   "frame channels written beside the colour as layers of the .exr output: depth (Z), normal "
                   "(normal.X/Y/Z, world space), albedo (albedo.R/G/B); comma-separated or repeated")
        ->delimiter(',');
    app.add_flag("--exr-half", options.exrHalf, "the .exr output's colour, normal and albedo as 16-bit half floats (depth stays 32-bit)");
    app.add_option("--view", options.view,
                   "a view-state file (ripple-view writes them with V): its camera, renderer settings and size "
                   "where the command line does not set them, and its light, volume and iso-surface values (give "
                   "the same scene as to ripple-view)");
    app.add_option("--ambient", options.ambient, "ambient radiance (default: what the scene suggests; 0 with --environment)")
        ->check(CLI::NonNegativeNumber);
    addEnvironmentOptions(app, options.environment);
    app.add_flag("-q,--quiet", options.quiet, "no progress line and no warnings");
    app.add_option("--partition", options.partition,
                   "under mpirun, each rank imports: round-robin (whole mesh instances dealt in turn) or spatial "
                   "(the triangles of one k-d region per rank)")
        ->capture_default_str();
    app.add_option("--resource-root", options.resourceRoot,
                   "folder the scene's buffer and image URIs may reach (default: the scene file's folder); "
                   "for trusted input only")
        ->check(CLI::ExistingDirectory);
    addVolumeOptions(app, options.field);
    app.add_flag("--list-devices", options.listDevices,
                 "list the Vulkan devices the ANARI device sees (index, name, kind, driver), mark the one it renders "
                 "with, and exit");
    app.add_flag("--stats", options.stats, "print per-rank triangles, scene memory, rays and bytes sent per frame, and "
                                           "GPU time per frame by stage of the wavefront loop");
}

// Under mpirun: the options every rank must share, and whether its command line parsed (exit code + 1, 0
// when it did), so that ranks whose command lines differ all stop with one message.
std::vector<AgreedOption> agreedOptions(const Options& options, int parseOutcome) {
    const auto number = [](double value) {
        uint64_t bits = 0;
        std::memcpy(&bits, &value, sizeof bits);
        return bits;
    };
    const std::string volumeOptions = describeVolumeOptions(options.field);
    std::string channelList;
    for (const std::string& channel : options.channels) channelList += channel + ",";
    const std::string scene = !options.field.volume.empty() ? "--volume " + options.field.volume
                              : options.scene.empty() ? "--demo " + options.demo
                                                      : "file " + options.scene;
    return {{"command lines (some ranks could not parse theirs)", uint64_t(parseOutcome), false},
            {"scenes (a file, or --demo)", optionHash(scene), false},
            {"--volume options (--dims, --type, --spacing, --tf, --opacity, --unit-distance, --isovalue)",
             optionHash(volumeOptions), false},
            {"--spp", options.spp, true},
            {"--size", optionHash(options.size), false},
            {"--time", options.seconds ? number(*options.seconds) : 0, false},
            {"--target-error", options.targetError ? number(*options.targetError) : 0, false},
            {"--max-path-length", options.maxPathLength, true},
            {"--seed", options.seed, true},
            {"--camera", options.camera ? uint64_t(int64_t(*options.camera) + 2) : 0, false},
            {"--ambient", options.ambient ? number(*options.ambient) : 0, false},
            {"--environment", optionHash(options.environment.file), false},
            {"--environment-intensity", number(options.environment.intensity), false},
            {"--environment-rotation", number(options.environment.rotationDegrees), false},
            {"--partition", optionHash(options.partition), false},
            {"--traversal", optionHash(options.traversal), false},
            {"--exchange", optionHash(options.exchange), false},
            {"--library", optionHash(options.library), false},
            {"--reference", optionHash(options.reference), false},
            {"--report", optionHash(options.report), false},
            {"--view", optionHash(options.view), false},
            {"--channels", optionHash(channelList), false},
            {"--exr-half", uint64_t(options.exrHalf), false},
            {"--list-devices", uint64_t(options.listDevices), false}};
}

// --view: the file's camera replaces the scene's, and its renderer settings and size apply where the command
// line does not set them (the file's pixelSamples is the viewer's pass size: --spp counts here).
void applyViewState(Options& options, const CLI::App& app) {
    if (options.view.empty()) return;
    if (options.camera) throw std::runtime_error("give one of --camera and --view");
    const ViewState state = readViewState(options.view);
    if (state.size && app.count("--size") == 0) options.size = std::to_string(state.size->x) + "x" + std::to_string(state.size->y);
    if (state.maxPathLength && app.count("--max-path-length") == 0) options.maxPathLength = uint32_t(*state.maxPathLength);
    if (state.renderer && app.count("--renderer") == 0) options.renderer = *state.renderer;
    if (state.traversal && app.count("--traversal") == 0) options.traversal = *state.traversal;
    options.viewState = state;
}

}  // namespace ripple::apps
