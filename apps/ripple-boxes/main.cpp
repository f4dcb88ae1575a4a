// ripple-boxes: the 4x4x4 boxes of the data-parallel ANARI paper, each rank holding its own share of them
// (run it under mpirun); rank 0 writes the image. --bench times frames and reports what crossed ranks;
// --compare renders natively, through the compositing device and on one rank, and measures the difference.
#include "apps/ripple-boxes/BoxesScene.h"
#include "apps/scene/AnariParams.h"
#include "apps/scene/ImageSize.h"
#include "io/FileWrite.h"
#include "io/image/ImageIO.h"
#include "mpi/Communicator.h"
#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {
namespace {

struct Options {
    std::string output = "boxes.png";
    std::string size = "512x512";
    uint32_t spp = 4;
    uint32_t maxPathLength = 3;
    uint32_t tessellation = 1;
    std::string library = "ripple";
    bool bench = false;
    uint32_t frames = 5;
    std::string json = "ripple-boxes-bench.json";
    std::string compare;  // --compare PREFIX: the three-way comparison instead of one image
    std::string exchange = "bounds";  // the device parameter rayExchange
    std::string partition = "random";
};

BoxesPartition partitionOf(const Options& options) {
    return options.partition == "slabs" ? BoxesPartition::Slabs : BoxesPartition::Random;
}

struct StatusLog {
    int rank = 0;
    int errors = 0;
};

void onStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
              ANARIStatusCode, const char* message) {
    auto* log = static_cast<StatusLog*>(const_cast<void*>(user));
    if (severity > ANARI_SEVERITY_WARNING) return;
    if (severity <= ANARI_SEVERITY_ERROR) ++log->errors;
    std::fprintf(stderr, "[ripple-boxes] rank %d %s: %s\n", log->rank,
                 severity <= ANARI_SEVERITY_ERROR ? "ERROR" : "WARNING", message ? message : "(no message)");
}

// What one rank measured in --bench mode; gathered on rank 0 as plain bytes.
struct RankReport {
    uint64_t boxes = 0;
    uint64_t triangles = 0;
    uint64_t sceneBytes = 0;
    uint64_t peakRssKiB = 0;
    uint64_t raysSent = 0;   // per frame, averaged over the timed frames
    uint64_t bytesSent = 0;
    uint64_t raysReceived = 0;
    uint64_t raysTraced = 0;  // its own rays
    uint64_t exchangeRounds = 0;
    uint64_t visitMicroseconds = 0;
    double secondsPerFrame = 0.0;

    uint64_t work() const { return raysTraced + raysReceived; }
};

// The whole run's traffic: bytes per ray-hop over all ranks, and the busiest rank's traced rays (its own
// and visitors) over the mean.
struct BenchSummary {
    double secondsPerFrame = 0.0;  // the slowest rank's
    double bytesPerRankFrame = 0.0;
    double bytesPerRayHop = 0.0;
    double raysSentPerRank = 0.0;
    double loadImbalance = 1.0;
};

BenchSummary summarize(const std::vector<RankReport>& ranks) {
    BenchSummary s;
    uint64_t bytes = 0, rays = 0, work = 0, busiest = 0;
    for (const RankReport& r : ranks) {
        s.secondsPerFrame = std::max(s.secondsPerFrame, r.secondsPerFrame);
        bytes += r.bytesSent;
        rays += r.raysSent;
        work += r.work();
        busiest = std::max(busiest, r.work());
    }
    const double n = double(ranks.size());
    s.bytesPerRankFrame = double(bytes) / n;
    s.bytesPerRayHop = rays > 0 ? double(bytes) / double(rays) : 0.0;
    s.raysSentPerRank = double(rays) / n;
    s.loadImbalance = work > 0 ? double(busiest) / (double(work) / n) : 1.0;
    return s;
}

// The library, device and objects of the run, released in reverse order; the device's last release is
// collective, so every rank must get here.
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

uint64_t frameCounter(ANARIDevice device, ANARIFrame frame, const char* name) {
    uint64_t value = 0;
    anariGetProperty(device, frame, name, ANARI_UINT64, &value, sizeof value, ANARI_WAIT);
    return value;
}

void writeJson(const std::string& path, const Options& options, glm::uvec2 size, const std::vector<RankReport>& ranks) {
    std::ostringstream out;
    const BenchSummary sum = summarize(ranks);
    out << "{\n  \"ranks\": " << ranks.size() << ",\n  \"exchange\": \"" << options.exchange
        << "\",\n  \"partition\": \"" << options.partition << "\",\n  \"width\": " << size.x << ",\n  \"height\": " << size.y
        << ",\n  \"spp\": " << options.spp << ",\n  \"maxPathLength\": " << options.maxPathLength
        << ",\n  \"tessellation\": " << options.tessellation << ",\n  \"frames\": " << options.frames
        << ",\n  \"secondsPerFrame\": " << sum.secondsPerFrame << ",\n  \"bytesPerRankFrame\": " << sum.bytesPerRankFrame
        << ",\n  \"bytesPerRayHop\": " << sum.bytesPerRayHop << ",\n  \"raysSentPerRank\": " << sum.raysSentPerRank
        << ",\n  \"loadImbalance\": " << sum.loadImbalance << ",\n  \"perRank\": [\n";
    for (size_t r = 0; r < ranks.size(); ++r) {
        const RankReport& x = ranks[r];
        out << "    {\"rank\": " << r << ", \"boxes\": " << x.boxes << ", \"triangles\": " << x.triangles
            << ", \"sceneBytes\": " << x.sceneBytes << ", \"peakRssKiB\": " << x.peakRssKiB
            << ", \"raysSentPerFrame\": " << x.raysSent << ", \"bytesSentPerFrame\": " << x.bytesSent
            << ", \"raysReceivedPerFrame\": " << x.raysReceived << ", \"raysTracedPerFrame\": " << x.raysTraced
            << ", \"exchangeRoundsPerFrame\": " << x.exchangeRounds
            << ", \"visitSecondsPerFrame\": " << double(x.visitMicroseconds) * 1e-6
            << ", \"secondsPerFrame\": " << x.secondsPerFrame << "}" << (r + 1 < ranks.size() ? "," : "") << "\n";
    }
    out << "  ]\n}\n";
    writeFileAtomically(path, out.str(), "the benchmark results");
}

void printBench(glm::uvec2 size, const Options& options, const std::vector<RankReport>& ranks) {
    std::printf("ripple-boxes bench: %zu rank(s), %s exchange, %s partition, %ux%u, %u spp per frame, %u timed frames\n",
                ranks.size(), options.exchange.c_str(), options.partition.c_str(), size.x, size.y, options.spp,
                options.frames);
    std::printf("%5s %6s %10s %10s %9s %13s %12s %13s %13s %9s\n", "rank", "boxes", "triangles", "scene MiB", "RSS MiB",
                "rays sent/fr", "MiB sent/fr", "visitors/fr", "own rays/fr", "s/frame");
    for (size_t r = 0; r < ranks.size(); ++r) {
        const RankReport& x = ranks[r];
        std::printf("%5zu %6llu %10llu %10.2f %9.1f %13llu %12.2f %13llu %13llu %9.3f\n", r, (unsigned long long)x.boxes,
                    (unsigned long long)x.triangles, double(x.sceneBytes) / 1048576.0, double(x.peakRssKiB) / 1024.0,
                    (unsigned long long)x.raysSent, double(x.bytesSent) / 1048576.0,
                    (unsigned long long)x.raysReceived, (unsigned long long)x.raysTraced, x.secondsPerFrame);
    }
    const BenchSummary s = summarize(ranks);
    std::printf("per frame: %.3f s, %.2f MiB per rank, %.1f bytes per ray-hop, %.0f rays sent per rank, load "
                "imbalance %.2f (busiest rank's traced rays over the mean)\n",
                s.secondsPerFrame, s.bytesPerRankFrame / 1048576.0, s.bytesPerRayHop, s.raysSentPerRank, s.loadImbalance);
}

ANARIFrame makeFrame(Session& s, const Options& options, glm::uvec2 size, ANARIWorld world, ANARIDataType colorType);

void openDevice(Session& s, const std::string& library, StatusLog& log) {
    s.library = anariLoadLibrary(library.c_str(), onStatus, &log);
    if (!s.library) throw std::runtime_error("cannot load the ANARI library '" + library + "'");
    s.device = anariNewDevice(s.library, "default");
    if (!s.device) throw std::runtime_error("the ANARI library '" + library + "' created no device");
}

// --- --compare: the paper's three-way figure ----------------------------------------------------------

enum class Way { Native, Composited, Single };

// One render of the comparison: native data-parallel Ripple and Ripple through ripple_ptc on every rank
// (each rank holding its share; compositing needs the lights on every rank, the native device gathers
// them), or on rank 0 alone a Ripple device told to render alone (MPI_COMM_SELF) holding every box.
// Linear RGBA, bottom row first, on rank 0; empty elsewhere.
std::vector<float> renderWay(const Options& options, glm::uvec2 size, const mpi::Communicator& ranks, Way way) {
    StatusLog log{ranks.rank(), 0};
    Session s;
    openDevice(s, way == Way::Composited ? "ripple_ptc" : "ripple", log);
    ANARIDevice d = s.device;
    if (way == Way::Single) {
        if (const void* self = mpi::Communicator::selfHandle())
            anariSetParameter(d, d, "mpiCommunicator", ANARI_VOID_POINTER, self);
        anariCommitParameters(d, d);
    } else if (way == Way::Native) {
        anariSetParameter(d, d, "rayExchange", ANARI_STRING, options.exchange.c_str());
        anariCommitParameters(d, d);
    }
    const bool alone = way == Way::Single;
    const BoxesPart part = buildBoxesPart(d, alone ? 0u : uint32_t(ranks.rank()), alone ? 1u : uint32_t(ranks.size()),
                                          options.tessellation, way == Way::Composited, partitionOf(options));
    s.objects.push_back(part.world);
    ANARIFrame frame = makeFrame(s, options, size, part.world, ANARI_FLOAT32_VEC4);
    anariRenderFrame(d, frame);
    anariFrameReady(d, frame, ANARI_WAIT);
    if (log.errors > 0) throw std::runtime_error("the device reported errors (above)");
    if (ranks.rank() != 0) return {};
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const auto* pixels = static_cast<const float*>(anariMapFrame(d, frame, "channel.color", &width, &height, &type));
    std::vector<float> image;
    if (pixels && width == size.x && height == size.y && type == ANARI_FLOAT32_VEC4)
        image.assign(pixels, pixels + size_t(width) * height * 4);
    if (pixels) anariUnmapFrame(d, frame, "channel.color");
    if (image.empty()) throw std::runtime_error("the device returned no FLOAT32_VEC4 color channel of the requested size");
    return image;
}

// A pixel "differs" when one of its linear RGB components is more than this apart.
constexpr float kDifferThreshold = 0.05f;

struct Difference {
    double differing = 0.0;  // fraction of pixels
    double brighter = 0.0;   // fraction of pixels where `test` is brighter by the threshold (luminance)
    double darker = 0.0;
    double meanAbs = 0.0;    // mean |test - reference| over pixels and RGB
};

float luminance(const float* rgba) { return 0.2126f * rgba[0] + 0.7152f * rgba[1] + 0.0722f * rgba[2]; }

Difference difference(const std::vector<float>& test, const std::vector<float>& reference) {
    Difference d;
    const size_t pixels = test.size() / 4;
    for (size_t p = 0; p < pixels; ++p) {
        const float* a = &test[p * 4];
        const float* b = &reference[p * 4];
        float largest = 0.0f;
        for (int c = 0; c < 3; ++c) {
            largest = std::max(largest, std::abs(a[c] - b[c]));
            d.meanAbs += std::abs(a[c] - b[c]);
        }
        d.differing += largest > kDifferThreshold;
        d.brighter += luminance(a) > luminance(b) + kDifferThreshold;
        d.darker += luminance(a) < luminance(b) - kDifferThreshold;
    }
    d.differing /= double(pixels);
    d.brighter /= double(pixels);
    d.darker /= double(pixels);
    d.meanAbs /= 3.0 * double(pixels);
    return d;
}

void printDifference(const char* what, const Difference& d) {
    std::printf("%-26s %9.2f%% %10.4f %12.2f%% %11.2f%%\n", what, 100.0 * d.differing, d.meanAbs, 100.0 * d.brighter,
                100.0 * d.darker);
}

int runCompare(const Options& options, const mpi::Communicator& ranks) {
    const glm::uvec2 size = parseImageSize(options.size);
    const std::vector<float> native = renderWay(options, size, ranks, Way::Native);
    const std::vector<float> composited = renderWay(options, size, ranks, Way::Composited);
    if (ranks.rank() != 0) return 0;
    const std::vector<float> single = renderWay(options, size, ranks, Way::Single);

    // The difference image: red where compositing is brighter than native (shadows and occlusion it
    // cannot see), blue where darker (light from other ranks it misses), four times the luminance gap.
    std::vector<float> diff(composited.size(), 1.0f);
    for (size_t p = 0; p < diff.size() / 4; ++p) {
        const float gap = luminance(&composited[p * 4]) - luminance(&native[p * 4]);
        diff[p * 4] = std::min(1.0f, 4.0f * std::max(gap, 0.0f));
        diff[p * 4 + 1] = 0.0f;
        diff[p * 4 + 2] = std::min(1.0f, 4.0f * std::max(-gap, 0.0f));
    }
    const std::string prefix = options.compare;
    writePngFromLinearBottomUp(prefix + "-native.png", size.x, size.y, native.data());
    writePngFromLinearBottomUp(prefix + "-composited.png", size.x, size.y, composited.data());
    writePngFromLinearBottomUp(prefix + "-single.png", size.x, size.y, single.data());
    writePngFromLinearBottomUp(prefix + "-difference.png", size.x, size.y, diff.data());

    std::printf("ripple-boxes --compare: %d rank(s), %ux%u, %u spp, paths of %u; a pixel differs when an RGB "
                "component is %.2f apart\n",
                ranks.size(), size.x, size.y, options.spp, options.maxPathLength, double(kDifferThreshold));
    std::printf("%-26s %10s %10s %13s %12s\n", "", "differ", "mean |d|", "brighter", "darker");
    printDifference("composited vs native", difference(composited, native));
    printDifference("composited vs single-rank", difference(composited, single));
    printDifference("native vs single-rank", difference(native, single));
    std::printf("wrote %s-{native,composited,single,difference}.png\n", prefix.c_str());
    return 0;
}

// The camera, renderer and committed frame of the boxes view over `world` (all kept in the session).
ANARIFrame makeFrame(Session& s, const Options& options, glm::uvec2 size, ANARIWorld world, ANARIDataType colorType) {
    ANARIDevice d = s.device;
    const BoxesView view;
    ANARICamera camera = anariNewCamera(d, "perspective");
    s.objects.push_back(camera);
    anari::set(d, camera, "position", view.position);
    anari::set(d, camera, "direction", view.target - view.position);
    anari::set(d, camera, "up", view.up);
    anari::set(d, camera, "fovy", view.fovy);
    anari::set(d, camera, "aspect", float(size.x) / float(size.y));
    anariCommitParameters(d, camera);

    ANARIRenderer renderer = anariNewRenderer(d, "default");
    s.objects.push_back(renderer);
    anari::set(d, renderer, "pixelSamples", int32_t(options.spp));
    anari::set(d, renderer, "maxPathLength", int32_t(options.maxPathLength));
    anari::set(d, renderer, "background", glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    anariCommitParameters(d, renderer);

    ANARIFrame frame = anariNewFrame(d);
    s.objects.push_back(frame);
    anari::set(d, frame, "size", size);
    anariSetParameter(d, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    anari::setObject(d, frame, "world", ANARI_WORLD, world);
    anari::setObject(d, frame, "renderer", ANARI_RENDERER, renderer);
    anari::setObject(d, frame, "camera", ANARI_CAMERA, camera);
    anariCommitParameters(d, frame);

    return frame;
}

int run(const Options& options, const mpi::Communicator& ranks) {
    const glm::uvec2 size = parseImageSize(options.size);
    const auto rank = uint32_t(ranks.rank()), rankCount = uint32_t(ranks.size());
    const bool pfm = std::filesystem::path(options.output).extension() == ".pfm";

    StatusLog log{ranks.rank(), 0};
    Session s;
    openDevice(s, options.library, log);
    ANARIDevice d = s.device;
    anariSetParameter(d, d, "rayExchange", ANARI_STRING, options.exchange.c_str());
    anariCommitParameters(d, d);

    const BoxesPart part = buildBoxesPart(d, rank, rankCount, options.tessellation, false, partitionOf(options));
    s.objects.push_back(part.world);

    const ANARIDataType colorType = pfm ? ANARI_FLOAT32_VEC4 : ANARI_UFIXED8_RGBA_SRGB;
    ANARIFrame frame = makeFrame(s, options, size, part.world, colorType);

    // anariRenderFrame is collective: every rank renders every frame. The first frame builds the scene;
    // --bench times the ones after it.
    anariRenderFrame(d, frame);
    anariFrameReady(d, frame, ANARI_WAIT);
    if (log.errors > 0) throw std::runtime_error("the device reported errors (above)");

    if (options.bench) {
        RankReport mine;
        mine.boxes = part.boxes;
        mine.triangles = part.triangles;
        const auto start = std::chrono::steady_clock::now();
        for (uint32_t f = 0; f < options.frames; ++f) {
            anariRenderFrame(d, frame);
            anariFrameReady(d, frame, ANARI_WAIT);
            mine.raysSent += frameCounter(d, frame, "ripple.raysSent");
            mine.bytesSent += frameCounter(d, frame, "ripple.bytesSent");
            mine.raysReceived += frameCounter(d, frame, "ripple.raysReceived");
            mine.raysTraced += frameCounter(d, frame, "ripple.raysTraced");
            mine.exchangeRounds += frameCounter(d, frame, "ripple.exchangeRounds");
            mine.visitMicroseconds += frameCounter(d, frame, "ripple.visitMicroseconds");
        }
        mine.secondsPerFrame =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / options.frames;
        mine.raysSent /= options.frames;
        mine.bytesSent /= options.frames;
        mine.raysReceived /= options.frames;
        mine.raysTraced /= options.frames;
        mine.exchangeRounds /= options.frames;
        mine.visitMicroseconds /= options.frames;
        mine.sceneBytes = frameCounter(d, frame, "ripple.sceneBytes");
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        mine.peakRssKiB = uint64_t(usage.ru_maxrss);
        const auto bytes = std::span(reinterpret_cast<const uint8_t*>(&mine), sizeof mine);
        const std::vector<std::vector<uint8_t>> all = ranks.gatherToRoot(bytes);
        if (rank == 0) {
            std::vector<RankReport> reports(all.size());
            for (size_t r = 0; r < all.size(); ++r) std::memcpy(&reports[r], all[r].data(), sizeof(RankReport));
            printBench(size, options, reports);
            writeJson(options.json, options, size, reports);
            std::printf("wrote %s\n", options.json.c_str());
        }
    }
    if (log.errors > 0) throw std::runtime_error("the device reported errors (above)");

    // Only rank 0 holds the final image (data-parallel ANARI); the other ranks' frames are undefined.
    if (rank != 0) return 0;
    uint32_t width = 0, height = 0;
    ANARIDataType mappedType = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(d, frame, "channel.color", &width, &height, &mappedType);
    if (!pixels || width != size.x || height != size.y || mappedType != colorType) {
        if (pixels) anariUnmapFrame(d, frame, "channel.color");
        throw std::runtime_error("the device returned no color channel of the requested size and type");
    }
    try {
        if (pfm) writePfmBottomUp(options.output, width, height, static_cast<const float*>(pixels));
        else writePngBottomUp(options.output, width, height, static_cast<const uint8_t*>(pixels));
    } catch (...) {
        anariUnmapFrame(d, frame, "channel.color");
        throw;
    }
    anariUnmapFrame(d, frame, "channel.color");
    std::printf("rank 0 of %u wrote %s (%ux%u, %u spp, %u boxes on this rank)\n", rankCount, options.output.c_str(),
                width, height, options.spp, part.boxes);
    return 0;
}

}  // namespace
}  // namespace ripple::apps

int main(int argc, char** argv) {
    ripple::mpi::Runtime runtime(&argc, &argv);
    // Made before anything can fail: duplicating the communicator is collective, so no rank may do it
    // alone on an error path.
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();

    ripple::apps::Options options;
    CLI::App app{"ripple-boxes: the 4x4x4 boxes of the data-parallel ANARI paper, dealt to the MPI ranks "
                 "(run under mpirun; rank 0 writes the image)"};
    app.add_option("-o,--output", options.output, "output image on rank 0: .png (8-bit sRGB) or .pfm (linear float)")
        ->capture_default_str();
    app.add_option("--size", options.size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--spp", options.spp, "samples per pixel (per frame in --bench)")
        ->check(CLI::Range(1u, 4096u))->capture_default_str();
    app.add_option("--max-path-length", options.maxPathLength, "surface interactions per path")
        ->check(CLI::Range(1u, 64u))->capture_default_str();
    app.add_option("--tessellation", options.tessellation, "each box side cut into NxN quads (more triangles)")
        ->check(CLI::Range(1u, 512u))->capture_default_str();
    app.add_option("--library", options.library, "ANARI library name")->capture_default_str();
    app.add_option("--exchange", options.exchange,
                   "how rays cross ranks (device parameter rayExchange): bounds (only to ranks whose world boxes "
                   "a ray enters) or ring (every ray through every rank)")
        ->check(CLI::IsMember({"bounds", "ring"}))->capture_default_str();
    app.add_option("--partition", options.partition,
                   "how boxes are dealt to ranks: random (the paper's: each rank's boxes spread over the stack) or "
                   "slabs (spatial: runs of the 16 columns, the floor cut under them)")
        ->check(CLI::IsMember({"random", "slabs"}))->capture_default_str();
    app.add_flag("--bench", options.bench,
                 "time frames; print per-rank rays and bytes sent, visitors traced, scene memory, bytes per ray-hop "
                 "and load imbalance; write JSON");
    app.add_option("--frames", options.frames, "timed frames in --bench")->check(CLI::Range(1u, 1000u))->capture_default_str();
    app.add_option("--json", options.json, "where --bench writes its numbers (rank 0)")->capture_default_str();
    app.add_option("--compare", options.compare,
                   "render three ways (native data-parallel, through ripple_ptc compositing, one rank holding "
                   "everything), write PREFIX-{native,composited,single,difference}.png, print how they differ")
        ->excludes("--bench");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // Every rank parses the same arguments and so reaches the same verdict; one rank speaks.
        return ranks.rank() == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    }

    try {
        return options.compare.empty() ? ripple::apps::run(options, ranks) : ripple::apps::runCompare(options, ranks);
    } catch (const std::exception& e) {
        // The other ranks may be waiting in a collective call for this one: end them all, never hang.
        if (ranks.distributed()) ranks.abort(std::string("ripple-boxes: ") + e.what());
        std::fprintf(stderr, "[ripple-boxes] ERROR: %s\n", e.what());
        return 1;
    }
}
