// What ripple-bench measured, and its two outputs: the stdout tables and the JSON file with every number.
#pragma once

#include "bench/ripple-bench/Agreement.h"
#include "bench/ripple-bench/Timing.h"

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace ripple::bench {

// One tracer on one ray set. The tables use the median of `runs`; the JSON has each run.
struct TracerRuns {
    bool ran = false;
    std::vector<Sample> runs;        // timed runs, warm-up excluded
    double roundTripSeconds = 0.0;   // Ripple: the host convenience call, upload and download included (wall)
};

struct KindResult {
    std::string kind;                // "primary", "shadow" or "bounce"
    bool anyHit = false;
    uint64_t rays = 0;
    TracerRuns ripple, embree;
    bool compared = false;           // both ran: `agreement` holds
    Agreement agreement;
    uint64_t rippleRunMismatches = 0;  // device-side launch vs host convenience call: should be 0
    double rippleOrderSeconds = 0.0;   // --ray-order morton: host time to sort the rays (not in the trace times)
};

struct BuildResult {
    bool ran = false;
    std::vector<Sample> runs;        // wall and CPU of each whole construction, warm-up excluded
    std::vector<double> bvhSeconds;  // Ripple: SceneReport::blasBuildSeconds of each run
    std::vector<double> asSeconds;   // Ripple, rayQuery back-end: SceneReport::accelerationStructureSeconds
};

struct SceneResult {
    std::string name;
    std::string backend = "software";  // Ripple's traversal back-end (--backend): "software" or "rayQuery"
    std::string source;              // the glTF path, or "generated"
    std::string status = "ok";       // "ok", "skipped" or "failed"
    std::string message;             // why it was skipped or failed
    uint64_t triangles = 0;
    uint64_t vertices = 0;
    BuildResult rippleBuild, embreeBuild;
    double rippleTlasSeconds = 0.0;  // core::SceneReport of the last build
    uint64_t rippleTrianglesSkipped = 0;
    uint64_t rippleGpuBytes = 0;
    // single-level kernel: the collapsed tree (its BVH2 is built again, untimed in the table, for the collapse).
    uint64_t bvh4Nodes = 0;
    uint64_t bvh4ChildSlotsUsed = 0;  // over all nodes; 4 * bvh4Nodes when every node is full
    uint32_t bvh4Depth = 0;
    uint64_t bvh4NodeBytes = 0;
    double bvh4CollapseSeconds = 0.0;
    std::string secondaryFrom;       // whose primary hits seeded the shadow and bounce rays
    std::vector<KindResult> kinds;
};

struct RunInfo {
    std::string vkDevice;
    std::string vkDriver;            // driver name and version (Context::driverVersion)
    std::string embreeVersion;       // empty with --no-embree
    std::string cpuModel;
    unsigned hardwareThreads = 0;
    int tbbThreads = 0;
    std::string lpNumThreads;        // LP_NUM_THREADS, empty when unset
    std::string lpNativeVectorWidth; // LP_NATIVE_VECTOR_WIDTH, empty when unset
    uint32_t width = 0, height = 0, repeat = 0, workgroup = 0;
    bool quick = false;
    std::string rayOrder = "none";   // --ray-order
    uint32_t bvhWidth = 2;           // --bvh-width
    bool singleLevel = false;        // the BVH4 kernel (--bvh-width 4 or --single-level)
    std::string nodes = "full";      // --nodes
    std::string traversal = "lanes";  // --traversal
    std::string features = "triangles";  // --features
};

void printTables(std::ostream& out, const RunInfo& info, const std::vector<SceneResult>& scenes);
void writeJson(const std::filesystem::path& path, const RunInfo& info, const std::vector<SceneResult>& scenes);

}  // namespace ripple::bench
