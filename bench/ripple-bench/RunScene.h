// One benchmark scene from start to finish: load or generate the mesh, build both BVHs, generate the ray
// sets, trace each with both tracers, compare.
#pragma once

#include "bench/ripple-bench/EmbreeTracer.h"
#include "bench/ripple-bench/Report.h"
#include "bench/ripple-bench/RippleTracer.h"

#include <filesystem>
#include <string>

namespace ripple::bench {

inline constexpr const char* kSceneNames[] = {"builtin", "bunny", "sponza", "procedural"};

struct SceneSettings {
    std::filesystem::path dataDir;
    uint32_t width = 1024;
    uint32_t height = 768;
    uint32_t repeat = 3;
};

struct Tracers {
    RippleTracer& ripple;
    EmbreeTracer* embree = nullptr;  // null with --no-embree
};

// Progress goes to stderr so stdout carries only the tables.
void progress(const std::string& scene, const std::string& what);

// Never throws: a missing file gives status "skipped", any other error "failed", each with a message.
SceneResult runScene(const std::string& name, const SceneSettings& settings, Tracers tracers);

}  // namespace ripple::bench
