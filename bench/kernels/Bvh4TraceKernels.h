// The BVH4 speed lever's GPU side: one triangle mesh uploaded as a collapsed 4-wide BVH (Bvh4Mesh) and the
// closest-hit and any-hit kernels that trace it (shaders/trace_*_bvh4.comp). Single level, triangles only:
// what ripple-bench traces with --bvh-width 4 or --single-level. The renderer's two-level kernels over the
// same node layout are core/render/TraceKernels.
#pragma once

#include "core/bvh/Bvh4Collapse.h"
#include "core/scene/SceneDescription.h"
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/shared/ray.h"

#include <span>
#include <vector>

namespace ripple::bvh {

struct Bvh4MeshOptions {
    uint32_t maxChildren = 4;  // 2: the BVH2 in this layout (see collapseToBvh4)
    bool compressed = false;   // 8-bit quantized child boxes (Bvh4CompressedNode, the *_bvh4q kernels)
    BuildOptions build;        // the scene's defaults give the same BVH2 as a core::Scene BLAS
};

class Bvh4Mesh {
public:
    // Builds the BVH2, collapses it, compresses it if asked, and uploads nodes and leaf-ordered triangles.
    // Throws std::invalid_argument naming the first non-finite vertex or out-of-range index.
    Bvh4Mesh(const vk::Context& context, const core::TriangleMesh& mesh, const Bvh4MeshOptions& options = {});

    uint32_t nodeCount() const { return nodeCount_; }
    bool compressed() const { return compressed_; }
    uint64_t nodeBytes() const { return nodeBytes_; }
    const Bvh4& tree() const { return tree_; }  // host copy of the nodes, for statistics and tests
    double collapseSeconds() const { return collapseSeconds_; }  // compression included
    VkDeviceAddress nodesAddress() const { return nodes_.address(); }
    VkDeviceAddress trianglesAddress() const { return triangles_.address(); }

private:
    Bvh4 tree_;
    uint32_t nodeCount_ = 0;
    bool compressed_ = false;
    uint64_t nodeBytes_ = 0;
    double collapseSeconds_ = 0.0;
    vk::Buffer nodes_, triangles_;
};

// How the lanes of a subgroup walk the tree. Lanes: each lane its own ray, stack and node fetches
// (traverse_bvh4.glsl). Packet: the subgroup walks one stack over the union of its rays' paths, each node
// fetched once for all lanes (traverse_bvh4_packet.glsl); the same hits, more box and triangle tests.
enum class Bvh4Traversal { Lanes, Packet };

class Bvh4TraceKernels {
public:
    // stepBudget: node visits plus triangle tests per ray (per subgroup with Packet) before the ray is
    // flagged HIT_FLAG_RAN_OUT; the same bounds as core::TraceOptions::stepBudget (lavapipe's silent loop
    // cap). Packet needs subgroups of at least 4 lanes with ballot, arithmetic and vote operations in
    // compute shaders, and a workgroup size that is a multiple of the subgroup size; otherwise it throws
    // std::invalid_argument saying which.
    Bvh4TraceKernels(const vk::Context& context, uint32_t workgroupSize = 64, uint32_t stepBudget = 30000,
                     Bvh4Traversal traversal = Bvh4Traversal::Lanes);

    void traceClosest(VkCommandBuffer cmd, const Bvh4Mesh& mesh, const vk::Buffer& rays, const vk::Buffer& hits,
                      uint32_t rayCount);
    void traceAny(VkCommandBuffer cmd, const Bvh4Mesh& mesh, const vk::Buffer& rays, const vk::Buffer& occluded,
                  uint32_t rayCount);

    // Host convenience: upload, trace, wait, download.
    std::vector<gpu::Hit> traceClosest(const Bvh4Mesh& mesh, std::span<const gpu::Ray> rays);
    std::vector<uint32_t> traceAny(const Bvh4Mesh& mesh, std::span<const gpu::Ray> rays);

private:
    void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, const Bvh4Mesh& mesh,
                  const vk::Buffer& rays, const vk::Buffer& results, VkDeviceSize resultStride, uint32_t rayCount);
    template <class Result>
    std::vector<Result> traceOnHost(const vk::ComputePipeline& pipeline, const Bvh4Mesh& mesh,
                                    std::span<const gpu::Ray> rays);

    const vk::ComputePipeline& closestPipeline(const Bvh4Mesh& mesh) const;
    const vk::ComputePipeline& anyPipeline(const Bvh4Mesh& mesh) const;

    const vk::Context& context_;
    uint32_t workgroupSize_, stepBudget_;
    // Of the chosen traversal only.
    vk::ComputePipeline closest_, any_, closestCompressed_, anyCompressed_;
};

}  // namespace ripple::bvh
