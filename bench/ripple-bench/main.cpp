// ripple-bench: builds Ripple's and Embree's BVHs over the same meshes, traces the same primary, shadow and
// diffuse-bounce rays with both, and reports speed (per wall second and per CPU second) and agreement.
#include "apps/scene/ImageSize.h"
#include "bench/ripple-bench/Report.h"
#include "bench/ripple-bench/RunScene.h"

#include <CLI/CLI.hpp>
#include <tbb/info.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#ifndef RIPPLE_DATA_DIR
#define RIPPLE_DATA_DIR "../shared/data"
#endif

namespace {

using namespace ripple;
using namespace ripple::bench;

struct Options {
    std::vector<std::string> scenes{std::begin(kSceneNames), std::end(kSceneNames)};
    std::string dataDir = RIPPLE_DATA_DIR;
    std::string size = "1024x768";
    uint32_t repeat = 3;
    uint32_t workgroup = core::TraceOptions{}.workgroupSize;
    std::string json = "ripple-bench.json";
    bool quick = false;
    bool noEmbree = false;
    std::string rayOrder = "none";
    uint32_t bvhWidth = 2;
    bool singleLevel = false;
    std::string nodes = "full";
    std::string traversal = "lanes";
    // The renderer specialises its kernels for the geometry kinds a scene has (FeatureSet), so the bench
    // measures the same by default; "all" is the unspecialised kernel the first measurements used.
    std::string features = "triangles";
    std::string backend = "all";
    uint32_t width = 0, height = 0;
};

// Returns false after printing help or an error; `exitCode` then holds what main should return.
bool parseOptions(int argc, char** argv, Options& o, int& exitCode) {
    CLI::App app{"ripple-bench: Ripple (Vulkan compute) vs Embree 3 on BVH build and ray tracing"};
    app.add_option("--scenes", o.scenes, "Comma-separated: builtin, bunny, sponza, procedural (default: all)")
        ->delimiter(',')
        ->check(CLI::IsMember({"builtin", "bunny", "sponza", "procedural"}));
    app.add_option("--data-dir", o.dataDir, "Folder holding gltf/bunny.glb and gltf/sponza-lod4-geometry.glb")
        ->capture_default_str();
    CLI::Option* size = app.add_option("--size", o.size, "Primary rays as WxH")->capture_default_str();
    CLI::Option* repeat =
        app.add_option("--repeat", o.repeat, "Timed runs per trace, after one warm-up; the median is reported")
            ->check(CLI::Range(1u, 1000u))
            ->capture_default_str();
    app.add_option("--workgroup", o.workgroup, "Ripple trace kernel workgroup size (TraceOptions::workgroupSize)")
        ->check(CLI::Range(1u, 1024u))
        ->capture_default_str();
    app.add_option("--ray-order", o.rayOrder,
                   "Ripple traces each ray set in input order or sorted by a Morton code of origin, direction "
                   "octant and direction (results compared in input order)")
        ->check(CLI::IsMember({"none", "morton"}))
        ->capture_default_str();
    app.add_option("--bvh-width", o.bvhWidth,
                   "2: the renderer's two-level kernel (its BVH2s collapsed to compressed BVH4); 4: the BVH2 "
                   "collapsed to a BVH4 traced by the single-level kernel")
        ->check(CLI::IsMember({2u, 4u}))
        ->capture_default_str();
    app.add_flag("--single-level", o.singleLevel,
                 "With --bvh-width 2: the BVH2 traced by the single-level BVH4 kernel (the control for width)");
    app.add_option("--nodes", o.nodes,
                   "Single-level kernel only: full-precision child boxes or boxes quantized to 8 bits per bound")
        ->check(CLI::IsMember({"full", "compressed"}))
        ->capture_default_str();
    app.add_option("--traversal", o.traversal,
                   "Single-level kernel only: one ray per lane, or the lanes of a subgroup walking one stack "
                   "together with each node fetched once for all (subgroup packets)")
        ->check(CLI::IsMember({"lanes", "packet"}))
        ->capture_default_str();
    app.add_option("--features", o.features,
                   "Two-level kernel: all geometry kinds' tests, or specialised for triangles as the renderer "
                   "specialises it for a triangle-only scene")
        ->check(CLI::IsMember({"all", "triangles"}))
        ->capture_default_str();
    app.add_option("--backend", o.backend,
                   "Ripple's traversal back-end: its own BVH4 kernels (software), ray queries over Vulkan "
                   "acceleration structures (rayQuery), or each in turn (all: rayQuery only where the device has it)")
        ->check(CLI::IsMember({"software", "rayQuery", "all"}))
        ->capture_default_str();
    app.add_option("--json", o.json, "Where to write all numbers as JSON")->capture_default_str();
    app.add_flag("--quick", o.quick, "Smoke run: 256x192 rays and one timed run (unless --size/--repeat say)");
    app.add_flag("--no-embree", o.noEmbree, "Ripple only; secondary rays then start from Ripple's primary hits");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        exitCode = app.exit(e);
        return false;
    }
    if (o.quick && size->count() == 0) o.size = "256x192";
    if (o.quick && repeat->count() == 0) o.repeat = 1;
    try {
        const glm::uvec2 rays = ripple::apps::parseImageSize(o.size);
        o.width = rays.x;
        o.height = rays.y;
    } catch (const std::exception& e) {
        std::cerr << "ripple-bench: " << e.what() << "\n";
        exitCode = 2;
        return false;
    }
    if (uint64_t(o.width) * o.height > (1u << 26)) {
        std::cerr << "ripple-bench: --size " << o.size << " is more than 2^26 primary rays\n";
        exitCode = 2;
        return false;
    }
    return true;
}

std::string environment(const char* name) {
    const char* value = std::getenv(name);
    return value ? value : "";
}

std::string cpuModel() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
        }
    }
    return "unknown";
}

RunInfo describeRun(const Options& o, const RippleTracer& ripple) {
    RunInfo info;
    info.vkDevice = ripple.deviceName();
    info.vkDriver = ripple.driverVersion();
    info.embreeVersion = o.noEmbree ? "" : EmbreeTracer::version();
    info.cpuModel = cpuModel();
    info.hardwareThreads = std::thread::hardware_concurrency();
    info.tbbThreads = tbb::info::default_concurrency();
    info.lpNumThreads = environment("LP_NUM_THREADS");
    info.lpNativeVectorWidth = environment("LP_NATIVE_VECTOR_WIDTH");
    info.width = o.width;
    info.height = o.height;
    info.repeat = o.repeat;
    info.workgroup = o.workgroup;
    info.quick = o.quick;
    info.rayOrder = o.rayOrder;
    info.bvhWidth = o.bvhWidth;
    info.singleLevel = o.singleLevel || o.bvhWidth == 4;
    info.nodes = o.nodes;
    info.traversal = o.traversal;
    info.features = o.features;
    return info;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    int exitCode = 0;
    if (!parseOptions(argc, argv, options, exitCode)) return exitCode;

    try {
        core::TraceOptions traceOptions;
        traceOptions.workgroupSize = options.workgroup;
        const Levers levers{.bvhWidth = options.bvhWidth,
                            .singleLevel = options.singleLevel,
                            .trianglesOnly = options.features == "triangles",
                            .compressedNodes = options.nodes == "compressed",
                            .packetTraversal = options.traversal == "packet",
                            .mortonOrder = options.rayOrder == "morton"};
        std::vector<core::Traversal> backends;
        if (options.backend != "rayQuery") backends.push_back(core::Traversal::Software);
        if (options.backend == "rayQuery") backends.push_back(core::Traversal::RayQuery);
        if (options.backend == "all") {
            const vk::Context probe(vk::ContextOptions{.printDeviceChoice = false});
            if (probe.supportsRayQuery()) backends.push_back(core::Traversal::RayQuery);
            else std::cerr << "[ripple-bench] no ray queries on " << probe.deviceName() << " (lacks "
                           << probe.rayQueryMissing() << "): software back-end only\n";
        }
        std::unique_ptr<EmbreeTracer> embree;
        if (!options.noEmbree) embree = std::make_unique<EmbreeTracer>();

        // One tracer (context, kernels) per back-end in turn; each runs every scene, Embree beside it.
        const SceneSettings settings{options.dataDir, options.width, options.height, options.repeat};
        std::vector<SceneResult> results;
        std::optional<RunInfo> info;
        for (core::Traversal backend : backends) {
            traceOptions.traversal = backend;
            RippleTracer ripple(traceOptions, levers);
            std::cerr << "[ripple-bench] Vulkan device: " << ripple.deviceName() << ", driver "
                      << ripple.driverVersion() << ", back-end " << core::traversalName(ripple.traversal()) << "\n";
            for (const std::string& name : options.scenes) {
                results.push_back(runScene(name, settings, Tracers{ripple, embree.get()}));
                results.back().backend = core::traversalName(ripple.traversal());
            }
            if (!info) info = describeRun(options, ripple);
        }
        printTables(std::cout, *info, results);
        writeJson(options.json, *info, results);
        std::cerr << "[ripple-bench] wrote " << options.json << "\n";

        for (const SceneResult& r : results)
            if (r.status == "ok") return 0;
        std::cerr << "ripple-bench: no scene could run\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "ripple-bench: " << e.what() << "\n";
        return 1;
    }
}
