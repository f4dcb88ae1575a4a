// Ripple's side of ripple-bench: one Vulkan context and kernel set for the whole run, one core::Scene per
// benchmark scene, and the two ways to trace a ray set (host convenience call, device-side launch), each
// through the speed levers chosen (BVH width, ray order).
#pragma once

#include "bench/kernels/Bvh4TraceKernels.h"
#include "core/vk/Timestamps.h"
#include "bench/ripple-bench/Timing.h"
#include "core/render/TraceKernels.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/Context.h"

#include <memory>
#include <span>
#include <vector>

namespace ripple::bench {

// Variants of Ripple's tracing under test (issue 2's levers). The defaults are the renderer's own path.
struct Levers {
    // 2: core::Scene and core::TraceKernels (the renderer's path: two levels, every BVH2 collapsed to a
    // compressed BVH4). 4: the same BVH2 collapsed into a single-level BVH4 (bvh::Bvh4Mesh,
    // bvh::Bvh4TraceKernels); ray-for-ray the same leaves.
    uint32_t bvhWidth = 2;
    // With width 2: the BVH2 in the BVH4 layout and kernel (two children per node), which separates the
    // effect of width from that of the single-level kernel. Width 4 is always single-level.
    bool singleLevel = false;
    // Two-level kernel only: specialise it for triangles (FeatureSet), as the renderer does for a
    // triangle-only scene; otherwise it holds every geometry kind's test. (The single-level kernels only
    // know triangles.)
    bool trianglesOnly = true;
    // Single-level kernel only: child boxes quantized to 8 bits (64-byte nodes instead of 112).
    bool compressedNodes = false;
    // Single-level kernel only: the lanes of a subgroup walk one stack over the union of their rays' paths
    // and fetch each node once for all (bvh::Bvh4Traversal::Packet) instead of one ray per lane.
    bool packetTraversal = false;
    // Trace each ray set sorted by bvh::mortonRayKey; results go back to input order before anyone sees them.
    bool mortonOrder = false;
};

class RippleTracer {
public:
    RippleTracer(const core::TraceOptions& options, const Levers& levers);

    const std::string& deviceName() const { return context_.deviceName(); }
    const std::string& driverVersion() const { return context_.driverVersion(); }
    // The back-end TraceOptions::traversal resolved to; scenes are built for it.
    core::Traversal traversal() const { return kernels_.traversal(); }

    // One mesh, one identity instance. Returns the time of the core::Scene construction (validation, BVH
    // builds, upload); report().blasBuildSeconds is the BVH part of it.
    Sample build(const core::TriangleMesh& mesh);
    const core::SceneReport& report() const { return scene_->report(); }
    // single-level only (null otherwise): the collapsed mesh build() made after the timed scene builds.
    const bvh::Bvh4Mesh* bvh4() const { return bvh4_.get(); }

    // Host convenience: upload, trace, wait, download.
    std::vector<gpu::Hit> traceClosest(std::span<const gpu::Ray> rays);
    std::vector<uint32_t> traceAny(std::span<const gpu::Ray> rays);

    // Device-side: stage() uploads the rays and sizes the results once; each launch() is then one
    // submitAndWait around the kernel, with wall and process CPU time around it and GPU time from
    // timestamps at both ends of the command buffer.
    void stage(std::span<const gpu::Ray> rays, bool anyHit);
    double lastOrderSeconds() const { return orderSeconds_; }  // stage()'s Morton sort on the host
    Sample launch();
    std::vector<gpu::Hit> downloadHits() const;
    std::vector<uint32_t> downloadOccluded() const;

private:
    template <class Result>
    std::vector<Result> traceOnHost(std::span<const gpu::Ray> rays);
    void record(VkCommandBuffer cmd);

    Levers levers_;
    vk::Context context_;
    core::TraceKernels kernels_;
    bvh::Bvh4TraceKernels bvh4Kernels_;
    std::unique_ptr<bvh::Bvh4Mesh> bvh4_;
    std::vector<uint32_t> order_;  // Morton permutation of the staged rays; empty in input order
    double orderSeconds_ = 0.0;
    vk::Timestamps timestamps_;
    std::unique_ptr<core::Scene> scene_;
    vk::Buffer rays_, results_;
    uint32_t stagedCount_ = 0;
    bool stagedAnyHit_ = false;
};

}  // namespace ripple::bench
