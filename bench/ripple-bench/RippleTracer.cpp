// Ripple scene construction and trace launches as ripple-bench times them, through the chosen levers.
#include "bench/ripple-bench/RippleTracer.h"

#include "bench/kernels/RayOrder.h"

#include <stdexcept>
#include <type_traits>

namespace ripple::bench {

namespace {

vk::ContextOptions quietContext() {
    vk::ContextOptions options;
    options.printDeviceChoice = false;  // stdout carries only the tables; main names the device on stderr
    return options;
}

}  // namespace

RippleTracer::RippleTracer(const core::TraceOptions& options, const Levers& levers)
    : levers_(levers),
      context_(quietContext()),
      kernels_(context_, options),
      bvh4Kernels_(context_, options.workgroupSize, options.stepBudget,
                   levers.packetTraversal ? bvh::Bvh4Traversal::Packet : bvh::Bvh4Traversal::Lanes),
      timestamps_(context_, 2) {
    if (levers.bvhWidth != 2 && levers.bvhWidth != 4)
        throw std::invalid_argument("BVH width must be 2 or 4, not " + std::to_string(levers.bvhWidth));
    if (levers.compressedNodes && levers.bvhWidth == 2 && !levers.singleLevel)
        throw std::invalid_argument("--nodes chooses the single-level kernel's nodes (--bvh-width 4 or "
                                    "--single-level); the renderer's kernel always uses compressed nodes");
    if (levers.packetTraversal && levers.bvhWidth == 2 && !levers.singleLevel)
        throw std::invalid_argument("--traversal packet is the single-level kernel's (--bvh-width 4 or "
                                    "--single-level); the renderer's kernel traverses one ray per lane");
    if (kernels_.traversal() == core::Traversal::RayQuery && (levers.bvhWidth != 2 || levers.singleLevel))
        throw std::invalid_argument("--bvh-width 4 and --single-level choose software kernels; use --backend software");
    if (levers.trianglesOnly) kernels_.useFeatures(gpu::FEATURE_TRIANGLES);
}

Sample RippleTracer::build(const core::TriangleMesh& mesh) {
    scene_.reset();  // free the previous scene's GPU memory before allocating the next
    bvh4_.reset();
    rays_ = {};
    results_ = {};
    core::SceneDescription description;
    description.meshes.push_back(mesh);  // copied outside the timed part
    description.instances.push_back(core::InstanceDescription{});
    const Sample s = measure([&] {
        scene_ = std::make_unique<core::Scene>(context_, description, bvh::BuildOptions{}, nullptr, kernels_.traversal());
    });
    // Untimed here: its BVH2 build and collapse are reported on their own (Bvh4Mesh's timers).
    if (levers_.bvhWidth == 4 || levers_.singleLevel)
        bvh4_ = std::make_unique<bvh::Bvh4Mesh>(
            context_, mesh,
            bvh::Bvh4MeshOptions{.maxChildren = levers_.bvhWidth, .compressed = levers_.compressedNodes});
    return s;
}

template <class Result>
std::vector<Result> RippleTracer::traceOnHost(std::span<const gpu::Ray> rays) {
    std::vector<uint32_t> order;
    std::vector<gpu::Ray> sorted;
    if (levers_.mortonOrder) {
        order = bvh::mortonRayOrder(rays);
        sorted = bvh::gatherInOrder(rays, std::span<const uint32_t>(order));
        rays = sorted;
    }
    std::vector<Result> results;
    if constexpr (std::is_same_v<Result, uint32_t>) {
        results = bvh4_ ? bvh4Kernels_.traceAny(*bvh4_, rays) : kernels_.traceAny(*scene_, rays);
    } else {
        results = bvh4_ ? bvh4Kernels_.traceClosest(*bvh4_, rays) : kernels_.traceClosest(*scene_, rays);
    }
    if (order.empty()) return results;
    return bvh::scatterFromOrder(std::span<const Result>(results), std::span<const uint32_t>(order));
}

std::vector<gpu::Hit> RippleTracer::traceClosest(std::span<const gpu::Ray> rays) {
    return traceOnHost<gpu::Hit>(rays);
}

std::vector<uint32_t> RippleTracer::traceAny(std::span<const gpu::Ray> rays) {
    return traceOnHost<uint32_t>(rays);
}

void RippleTracer::stage(std::span<const gpu::Ray> rays, bool anyHit) {
    if (rays.empty()) throw std::logic_error("RippleTracer::stage: no rays");
    rays_ = {};
    results_ = {};
    order_.clear();
    orderSeconds_ = 0.0;
    rays_ = vk::Buffer(context_, rays.size_bytes(), "bench rays");
    if (levers_.mortonOrder) {
        orderSeconds_ = measure([&] { order_ = bvh::mortonRayOrder(rays); }).wall;
        rays_.upload(std::span<const gpu::Ray>(bvh::gatherInOrder(rays, std::span<const uint32_t>(order_))));
    } else {
        rays_.upload(rays);
    }
    const size_t resultBytes = anyHit ? sizeof(uint32_t) : sizeof(gpu::Hit);
    results_ = vk::Buffer(context_, rays.size() * resultBytes, anyHit ? "bench occlusion" : "bench hits");
    stagedCount_ = uint32_t(rays.size());
    stagedAnyHit_ = anyHit;
}

void RippleTracer::record(VkCommandBuffer cmd) {
    if (bvh4_) {
        if (stagedAnyHit_) bvh4Kernels_.traceAny(cmd, *bvh4_, rays_, results_, stagedCount_);
        else bvh4Kernels_.traceClosest(cmd, *bvh4_, rays_, results_, stagedCount_);
    } else {
        if (stagedAnyHit_) kernels_.traceAny(cmd, *scene_, rays_, results_, stagedCount_);
        else kernels_.traceClosest(cmd, *scene_, rays_, results_, stagedCount_);
    }
}

Sample RippleTracer::launch() {
    Sample s = measure([&] {
        context_.submitAndWait([&](VkCommandBuffer cmd) {
            timestamps_.reset(cmd);
            timestamps_.write(cmd, 0);
            record(cmd);
            timestamps_.write(cmd, 1);
        });
    });
    s.gpu = timestamps_.seconds(0, 1);
    return s;
}

std::vector<gpu::Hit> RippleTracer::downloadHits() const {
    std::vector<gpu::Hit> hits(stagedAnyHit_ ? 0 : stagedCount_);
    results_.download(std::span<gpu::Hit>(hits));
    if (order_.empty()) return hits;
    return bvh::scatterFromOrder(std::span<const gpu::Hit>(hits), std::span<const uint32_t>(order_));
}

std::vector<uint32_t> RippleTracer::downloadOccluded() const {
    std::vector<uint32_t> occluded(stagedAnyHit_ ? stagedCount_ : 0);
    results_.download(std::span<uint32_t>(occluded));
    if (order_.empty()) return occluded;
    return bvh::scatterFromOrder(std::span<const uint32_t>(occluded), std::span<const uint32_t>(order_));
}

}  // namespace ripple::bench
