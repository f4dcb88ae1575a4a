// The phases of one benchmark scene, in the order they run; each phase is a function of its own.
#include "bench/ripple-bench/RunScene.h"

#include "bench/ripple-bench/GltfMeshes.h"
#include "bench/ripple-bench/ProceduralMeshes.h"
#include "bench/ripple-bench/RaySets.h"

#include <algorithm>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace ripple::bench {

namespace {

std::optional<core::TriangleMesh> loadMesh(const std::string& name, const SceneSettings& settings,
                                           SceneResult& result) {
    if (name == "builtin" || name == "procedural") {
        result.source = "generated";
        progress(name, "generating the mesh");
        return displacedCubeSphere(name == "builtin" ? kBuiltinSubdivision : kProceduralSubdivision);
    }
    if (name != "bunny" && name != "sponza") throw std::invalid_argument("unknown scene \"" + name + "\"");
    const std::filesystem::path file =
        settings.dataDir / "gltf" / (name == "bunny" ? "bunny.glb" : "sponza-lod4-geometry.glb");
    result.source = file.string();
    if (!std::filesystem::is_regular_file(file)) {
        result.status = "skipped";
        result.message = "no " + file.string() + " (set --data-dir to the folder holding gltf/)";
        progress(name, "skipped: " + result.message);
        return std::nullopt;
    }
    progress(name, "loading " + file.string());
    return loadGltfTriangles(file);
}

// Each BVH is built once untimed (thread pools and allocators warm up) and then `repeat` times timed.
void buildBoth(const core::TriangleMesh& mesh, const std::string& name, uint32_t repeat, Tracers tracers,
               SceneResult& result) {
    progress(name, "building Ripple scene x" + std::to_string(repeat + 1));
    tracers.ripple.build(mesh);
    for (uint32_t r = 0; r < repeat; ++r) {
        result.rippleBuild.runs.push_back(tracers.ripple.build(mesh));
        result.rippleBuild.bvhSeconds.push_back(tracers.ripple.report().blasBuildSeconds);
        if (tracers.ripple.traversal() == core::Traversal::RayQuery)
            result.rippleBuild.asSeconds.push_back(tracers.ripple.report().accelerationStructureSeconds);
    }
    result.rippleBuild.ran = true;
    const core::SceneReport& report = tracers.ripple.report();
    result.rippleTlasSeconds = report.tlasBuildSeconds;
    result.rippleTrianglesSkipped = report.trianglesSkipped;
    result.rippleGpuBytes = report.gpuBytes;
    for (const std::string& message : report.messages) progress(name, "Ripple scene: " + message);
    if (const bvh::Bvh4Mesh* bvh4 = tracers.ripple.bvh4()) {
        result.bvh4Nodes = bvh4->nodeCount();
        result.bvh4ChildSlotsUsed = bvh4->tree().childSlotsUsed;
        result.bvh4Depth = bvh4->tree().depth;
        result.bvh4CollapseSeconds = bvh4->collapseSeconds();
        result.bvh4NodeBytes = bvh4->nodeBytes();
        const double childrenPerNode = double(result.bvh4ChildSlotsUsed) / double(std::max<uint64_t>(1, result.bvh4Nodes));
        progress(name, "BVH4: " + std::to_string(result.bvh4Nodes) + " nodes, " + std::to_string(childrenPerNode) +
                           " children per node, depth " + std::to_string(result.bvh4Depth) + ", " +
                           std::to_string(result.bvh4NodeBytes >> 10) + " KiB, collapsed in " +
                           std::to_string(1e3 * result.bvh4CollapseSeconds) + " ms");
    }

    if (tracers.embree) {
        progress(name, "building Embree scene x" + std::to_string(repeat + 1));
        tracers.embree->build(mesh);
        for (uint32_t r = 0; r < repeat; ++r)
            result.embreeBuild.runs.push_back(measure([&] { tracers.embree->build(mesh); }));
        result.embreeBuild.ran = true;
    }
}

uint64_t countMismatches(std::span<const gpu::Hit> a, std::span<const gpu::Hit> b) {
    uint64_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const bool same = a[i].status == b[i].status &&
                          (a[i].status != gpu::HIT_FOUND || (a[i].primId == b[i].primId && a[i].t == b[i].t));
        n += !same;
    }
    return n;
}

uint64_t countMismatches(std::span<const uint32_t> a, std::span<const uint32_t> b) {
    uint64_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
}

// Result is gpu::Hit (closest-hit) or uint32_t (any-hit). Both tracers get one untimed warm-up, then
// `repeat` timed runs; the results of the last run are kept for comparison and for the next ray sets.
template <class Result>
KindResult traceBoth(const std::string& scene, const std::string& kind, std::span<const gpu::Ray> rays,
                     uint32_t repeat, Tracers tracers, std::vector<Result>& embreeOut, std::vector<Result>& rippleOut) {
    constexpr bool anyHit = std::is_same_v<Result, uint32_t>;
    KindResult k;
    k.kind = kind;
    k.anyHit = anyHit;
    k.rays = rays.size();
    if (rays.empty()) {
        progress(scene, kind + ": no rays (every primary ray missed)");
        return k;
    }

    if (tracers.embree) {
        progress(scene, kind + ": Embree, " + std::to_string(rays.size()) + " rays");
        embreeOut.resize(rays.size());
        auto trace = [&] {
            if constexpr (anyHit) tracers.embree->traceAny(rays, embreeOut);
            else tracers.embree->traceClosest(rays, embreeOut);
        };
        trace();
        for (uint32_t r = 0; r < repeat; ++r) k.embree.runs.push_back(measure(trace));
        k.embree.ran = true;
    }

    progress(scene, kind + ": Ripple, " + std::to_string(rays.size()) + " rays");
    // The host convenience call is the warm-up; its answers must equal those of the timed launches.
    std::vector<Result> host;
    k.ripple.roundTripSeconds = measure([&] {
        if constexpr (anyHit) host = tracers.ripple.traceAny(rays);
        else host = tracers.ripple.traceClosest(rays);
    }).wall;
    tracers.ripple.stage(rays, anyHit);
    k.rippleOrderSeconds = tracers.ripple.lastOrderSeconds();
    for (uint32_t r = 0; r < repeat; ++r) k.ripple.runs.push_back(tracers.ripple.launch());
    if constexpr (anyHit) rippleOut = tracers.ripple.downloadOccluded();
    else rippleOut = tracers.ripple.downloadHits();
    k.ripple.ran = true;
    k.rippleRunMismatches = countMismatches(std::span<const Result>(host), std::span<const Result>(rippleOut));
    if (k.rippleRunMismatches)
        progress(scene, kind + ": " + std::to_string(k.rippleRunMismatches) +
                            " rays differ between Ripple's host call and its device-side launch");

    if (tracers.embree) {
        k.compared = true;
        if constexpr (anyHit) k.agreement = compareAny(embreeOut, rippleOut);
        else k.agreement = compareClosest(embreeOut, rippleOut);
    }
    return k;
}

void traceAllKinds(const core::TriangleMesh& mesh, const std::string& name, const SceneSettings& settings,
                   Tracers tracers, SceneResult& result) {
    const Bounds bounds = meshBounds(mesh);
    progress(name, "generating primary rays");
    const std::vector<gpu::Ray> primary = primaryRays(bounds, settings.width, settings.height);
    std::vector<gpu::Hit> embreePrimary, ripplePrimary;
    result.kinds.push_back(traceBoth<gpu::Hit>(name, "primary", primary, settings.repeat, tracers, embreePrimary,
                                               ripplePrimary));

    // Embree's hits are the ground truth where Embree runs, so the secondary rays (and so the comparison
    // of them) do not depend on the tracer under test.
    result.secondaryFrom = tracers.embree ? "embree" : "ripple";
    progress(name, "generating shadow and bounce rays from " + result.secondaryFrom + "'s primary hits");
    const SecondaryRays secondary =
        secondaryRays(mesh, bounds, primary, tracers.embree ? embreePrimary : ripplePrimary);

    std::vector<uint32_t> embreeShadow, rippleShadow;
    result.kinds.push_back(traceBoth<uint32_t>(name, "shadow", secondary.shadow, settings.repeat, tracers,
                                               embreeShadow, rippleShadow));
    std::vector<gpu::Hit> embreeBounce, rippleBounce;
    result.kinds.push_back(traceBoth<gpu::Hit>(name, "bounce", secondary.bounce, settings.repeat, tracers,
                                               embreeBounce, rippleBounce));
}

}  // namespace

void progress(const std::string& scene, const std::string& what) {
    std::cerr << "[ripple-bench] " << scene << ": " << what << std::endl;
}

SceneResult runScene(const std::string& name, const SceneSettings& settings, Tracers tracers) {
    SceneResult result;
    result.name = name;
    try {
        const std::optional<core::TriangleMesh> mesh = loadMesh(name, settings, result);
        if (!mesh) return result;
        result.vertices = mesh->positions.size();
        result.triangles = mesh->indices.empty() ? mesh->positions.size() / 3 : mesh->indices.size();
        buildBoth(*mesh, name, settings.repeat, tracers, result);
        traceAllKinds(*mesh, name, settings, tracers, result);
    } catch (const std::exception& e) {
        result.status = "failed";
        result.message = e.what();
        progress(name, std::string("failed: ") + e.what());
    }
    return result;
}

}  // namespace ripple::bench
