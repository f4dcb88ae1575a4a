// ripple-render: renders a glTF file or a built-in demo scene to a PNG (or PFM) through any ANARI library,
// using only standard ANARI objects and parameters. Frames accumulate samples batch by batch.
#include "apps/common/AnariParams.h"
#include "apps/common/AnariScene.h"
#include "apps/common/DemoScene.h"
#include "apps/common/GltfScene.h"
#include "apps/common/ImageIO.h"
#include "apps/common/ScenePartition.h"
#include "apps/ripple-render/Progress.h"
#include "apps/ripple-render/RankStats.h"
#include "mpi/Communicator.h"
#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>

namespace ripple::apps {
namespace {

struct Options {
    std::string scene;                  // a .gltf/.glb, or empty for a demo scene
    std::string demo;
    std::string output = "ripple.png";
    std::string size = "512x512";
    uint32_t spp = 16;
    std::string library = "ripple";
    uint32_t maxPathLength = 5;
    std::optional<int> camera;
    std::optional<float> ambient;
    bool quiet = false;
    std::string partition = "round-robin";  // under mpirun: which share of the file each rank imports
    bool stats = false;
};

// The device's messages: errors always, warnings unless --quiet, chatter never.
struct StatusLog {
    bool quiet = false;
    int errors = 0;
};

void onStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
              ANARIStatusCode, const char* message) {
    auto* log = static_cast<StatusLog*>(const_cast<void*>(user));
    if (severity <= ANARI_SEVERITY_ERROR) {
        ++log->errors;
        std::fprintf(stderr, "[ripple-render] ERROR: %s\n", message ? message : "(no message)");
    } else if (severity <= ANARI_SEVERITY_PERFORMANCE_WARNING && !log->quiet) {
        std::fprintf(stderr, "[ripple-render] WARNING: %s\n", message ? message : "(no message)");
    }
}

glm::uvec2 parseSize(const std::string& text) {
    static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern)) throw std::runtime_error("--size '" + text + "' is not WIDTHxHEIGHT");
    const glm::uvec2 size(std::stoul(m[1]), std::stoul(m[2]));
    if (size.x == 0 || size.y == 0 || size.x > 16384 || size.y > 16384)
        throw std::runtime_error("--size " + text + ": each side must be 1 to 16384 pixels");
    return size;
}

// Samples per frame: the smallest divisor of spp that needs at most 16 frames, so the progress line moves
// and every frame carries the same count (changing pixelSamples may restart a device's accumulation).
uint32_t samplesPerFrame(uint32_t spp) {
    for (uint32_t batch = 1; batch < spp; ++batch)
        if (spp % batch == 0 && spp / batch <= 16) return batch;
    return spp;
}

// Whether the device lists `name` (e.g. "ANARI_KHR_FRAME_ACCUMULATION") in its "extension" property.
bool deviceHasExtension(ANARIDevice device, const char* name) {
    const char** extensions = nullptr;
    if (!anariGetProperty(device, device, "extension", ANARI_STRING_LIST, &extensions, sizeof extensions, ANARI_WAIT))
        return false;
    for (const char** e = extensions; e && *e; ++e)
        if (std::string(*e) == name) return true;
    return false;
}

// The library, its device and the objects of one render, released in reverse order whatever happens.
struct Session {
    ANARILibrary library = nullptr;
    ANARIDevice device = nullptr;
    std::vector<ANARIObject> objects;
    ~Session() {
        for (auto it = objects.rbegin(); it != objects.rend(); ++it) anariRelease(device, *it);
        if (device) anariRelease(device, device);
        if (library) anariUnloadLibrary(library);
    }
};

int render(const Options& options, const mpi::Communicator& ranks) {
    const PartitionKind partition = parsePartitionKind(options.partition);
    const bool root = ranks.rank() == 0;
    const glm::uvec2 size = parseSize(options.size);
    const bool pfm = std::filesystem::path(options.output).extension() == ".pfm";
    if (!options.scene.empty() && !options.demo.empty())
        throw std::runtime_error("give either a scene file or --demo, not both");
    const std::string demo = options.scene.empty() && options.demo.empty() ? "default" : options.demo;
    if (!demo.empty()) checkDemoSceneName(demo);

    // The file is read before any library is loaded, so a bad file fails fast and alone.
    std::optional<GltfScene> gltf;
    if (!options.scene.empty()) {
        gltf = loadGltf(options.scene);
        if (!options.quiet && root)
            for (const std::string& warning : gltf->warnings) std::fprintf(stderr, "[ripple-render] WARNING: %s\n", warning.c_str());
    }

    StatusLog log{options.quiet, 0};
    Session s;
    s.library = anariLoadLibrary(options.library.c_str(), onStatus, &log);
    if (!s.library)
        throw std::runtime_error("cannot load the ANARI library '" + options.library + "' (libanari_library_" +
                                 options.library + ".so)");
    s.device = anariNewDevice(s.library, "default");
    if (!s.device) throw std::runtime_error("the ANARI library '" + options.library + "' created no device");

    // Under mpirun each rank imports only its share of the file, so that no rank holds the whole scene;
    // the lights become ANARI lights on rank 0 alone (the device gathers every rank's lights).
    if (ranks.distributed() && !gltf)
        throw std::runtime_error("the demo scenes are not split over ranks: give a glTF file under mpirun");
    if (gltf && ranks.distributed() && partition == PartitionKind::RoundRobin && gltf->instances.size() < size_t(ranks.size()) &&
        root)
        std::fprintf(stderr, "[ripple-render] WARNING: %zu mesh instance(s) for %d ranks: some ranks hold nothing and one "
                     "holds whole meshes; --partition spatial splits meshes\n", gltf->instances.size(), ranks.size());
    if (gltf) gltf = partitionScene(*gltf, uint32_t(ranks.rank()), uint32_t(ranks.size()), partition);
    RankStats stats;
    stats.triangles = gltf ? gltf->trianglesDrawn() : 0;
    AnariWorld scene = gltf ? buildAnariWorld(s.device, *gltf, root) : buildDemoScene(s.device, demo);
    s.objects.push_back(scene.world);

    // Bounds as the device computed them; the scene's own where the device does not answer.
    float box[6];
    glm::vec3 lo = scene.boundsMin, hi = scene.boundsMax;
    if (anariGetProperty(s.device, scene.world, "bounds", ANARI_FLOAT32_BOX3, box, sizeof box, ANARI_WAIT)) {
        lo = glm::vec3(box[0], box[1], box[2]);
        hi = glm::vec3(box[3], box[4], box[5]);
    }
    const float aspect = float(size.x) / float(size.y);
    CameraView view;
    const int cameraIndex = options.camera.value_or(scene.cameras.empty() ? -1 : 0);
    if (cameraIndex >= 0) {
        if (size_t(cameraIndex) >= scene.cameras.size())
            throw std::runtime_error("--camera " + std::to_string(cameraIndex) + ": the scene has " +
                                     std::to_string(scene.cameras.size()) + " cameras");
        view = scene.cameras[size_t(cameraIndex)];
    } else {
        view = frameBounds(lo, hi, aspect);
    }
    ANARICamera camera = newAnariCamera(s.device, view, aspect);
    s.objects.push_back(camera);

    const uint32_t batch = samplesPerFrame(options.spp);
    ANARIRenderer renderer = anariNewRenderer(s.device, "default");
    if (!renderer) throw std::runtime_error("the device has no 'default' renderer");
    s.objects.push_back(renderer);
    anari::set(s.device, renderer, "pixelSamples", int32_t(batch));
    anari::set(s.device, renderer, "maxPathLength", int32_t(options.maxPathLength));
    anari::set(s.device, renderer, "background", scene.background);
    anari::set(s.device, renderer, "ambientRadiance", options.ambient.value_or(scene.ambientRadiance));
    anariCommitParameters(s.device, renderer);

    ANARIFrame frame = anariNewFrame(s.device);
    if (!frame) throw std::runtime_error("the device created no frame");
    s.objects.push_back(frame);
    const ANARIDataType colorType = pfm ? ANARI_FLOAT32_VEC4 : ANARI_UFIXED8_RGBA_SRGB;
    anari::set(s.device, frame, "size", size);
    anariSetParameter(s.device, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    if (deviceHasExtension(s.device, "ANARI_KHR_FRAME_ACCUMULATION")) anari::set(s.device, frame, "accumulation", true);
    anari::setObject(s.device, frame, "world", ANARI_WORLD, scene.world);
    anari::setObject(s.device, frame, "renderer", ANARI_RENDERER, renderer);
    anari::setObject(s.device, frame, "camera", ANARI_CAMERA, camera);
    anariCommitParameters(s.device, frame);

    const uint32_t frames = options.spp / batch;
    Progress progress(options.spp, !options.quiet && root);
    bool reportsRays = true;  // until the device says it has no such property (only Ripple has it)
    for (uint32_t f = 0; f < frames; ++f) {
        anariRenderFrame(s.device, frame);
        anariFrameReady(s.device, frame, ANARI_WAIT);
        float raysPerSecond = 0.0f;
        if (reportsRays)
            reportsRays = anariGetProperty(s.device, frame, "ripple.raysPerSecond", ANARI_FLOAT32, &raysPerSecond,
                                           sizeof raysPerSecond, ANARI_WAIT);
        progress.update((f + 1) * batch, reportsRays ? raysPerSecond : 0.0f);
        if (options.stats) {  // this rank's traffic in the frame just rendered
            uint64_t rays = 0, bytes = 0;
            anariGetProperty(s.device, frame, "ripple.raysSent", ANARI_UINT64, &rays, sizeof rays, ANARI_WAIT);
            anariGetProperty(s.device, frame, "ripple.bytesSent", ANARI_UINT64, &bytes, sizeof bytes, ANARI_WAIT);
            stats.raysSent += rays;
            stats.bytesSent += bytes;
            ++stats.frames;
        }
    }
    progress.finish();
    const double seconds = progress.elapsedSeconds();
    if (options.stats) {
        anariGetProperty(s.device, frame, "ripple.sceneBytes", ANARI_UINT64, &stats.sceneBytes, sizeof stats.sceneBytes,
                         ANARI_WAIT);
        printRankStats(ranks, stats);
    }
    // Only rank 0 holds the final image (data-parallel ANARI); the other ranks are done.
    if (!root) return log.errors > 0 ? 1 : 0;

    uint32_t width = 0, height = 0;
    ANARIDataType mappedType = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(s.device, frame, "channel.color", &width, &height, &mappedType);
    if (!pixels || width != size.x || height != size.y || mappedType != colorType) {
        if (pixels) anariUnmapFrame(s.device, frame, "channel.color");
        throw std::runtime_error("the device returned no " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                                 " color channel of the requested type");
    }
    try {
        if (pfm) writePfmBottomUp(options.output, width, height, static_cast<const float*>(pixels));
        else writePngBottomUp(options.output, width, height, static_cast<const uint8_t*>(pixels));
    } catch (...) {
        anariUnmapFrame(s.device, frame, "channel.color");
        throw;
    }
    anariUnmapFrame(s.device, frame, "channel.color");

    std::printf("rendered %ux%u, %u spp (%u frames of %u) in %.2f s -> %s\n", width, height, options.spp, frames,
                batch, seconds, options.output.c_str());
    if (log.errors > 0) {
        std::fprintf(stderr, "[ripple-render] ERROR: the device reported %d error(s); the image may be wrong\n", log.errors);
        return 1;
    }
    return 0;
}

}  // namespace
}  // namespace ripple::apps

int main(int argc, char** argv) {
    // Under mpirun every rank runs this program on its share of the scene (data-parallel ANARI).
    ripple::mpi::Runtime runtime(&argc, &argv);
    // Made before anything can fail: duplicating the communicator is collective.
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    using ripple::apps::Options;
    Options options;
    CLI::App app{"ripple-render: render a glTF 2.0 file or a built-in demo scene through an ANARI library"};
    app.add_option("scene", options.scene, "glTF 2.0 file (.gltf or .glb); without one a demo scene is rendered");
    std::string demoNames;
    for (const std::string& n : ripple::apps::demoSceneNames()) demoNames += (demoNames.empty() ? "" : ", ") + n;
    app.add_option("--demo", options.demo, "built-in scene: " + demoNames + " (default: default)");
    app.add_option("-o,--output", options.output, "output image: .png (8-bit sRGB) or .pfm (linear float)")->capture_default_str();
    app.add_option("--size", options.size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--spp", options.spp, "samples per pixel")->check(CLI::Range(1u, 1000000u))->capture_default_str();
    app.add_option("--library", options.library, "ANARI library name (loads libanari_library_NAME.so)")->capture_default_str();
    app.add_option("--max-path-length", options.maxPathLength, "surface interactions per path")
        ->check(CLI::Range(1u, 1024u))->capture_default_str();
    app.add_option("--camera", options.camera, "scene camera index; -1 frames the scene bounds (default: camera 0 if any)")
        ->check(CLI::Range(-1, 1 << 20));
    app.add_option("--ambient", options.ambient, "ambient radiance (default: what the scene suggests)")
        ->check(CLI::NonNegativeNumber);
    app.add_flag("-q,--quiet", options.quiet, "no progress line and no warnings");
    app.add_option("--partition", options.partition,
                   "under mpirun, each rank imports: round-robin (whole mesh instances dealt in turn) or spatial "
                   "(the triangles of one k-d region per rank)")
        ->capture_default_str();
    app.add_flag("--stats", options.stats, "print per-rank triangles, scene memory, rays and bytes sent per frame");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // Every rank parses the same arguments and reaches the same verdict; one rank speaks.
        return ranks.rank() == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    }

    try {
        return ripple::apps::render(options, ranks);
    } catch (const std::exception& e) {
        // Other ranks may wait for this one in a collective call: end them all, never hang.
        if (ranks.distributed()) ranks.abort(std::string("ripple-render: ") + e.what());
        std::fprintf(stderr, "[ripple-render] ERROR: %s\n", e.what());
        return 1;
    }
}
