// Host side of the BVH4 lever: mesh upload in the collapsed layout and the two single-level kernels.
#include "bench/kernels/Bvh4TraceKernels.h"

#include "core/render/TraceKernels.h"
#include "shaders/shared/scene.h"
#include "core/bvh/Bvh4Compress.h"
#include "shaders/trace_any_bvh4.spv.h"
#include "shaders/trace_any_bvh4p.spv.h"
#include "shaders/trace_any_bvh4q.spv.h"
#include "shaders/trace_any_bvh4qp.spv.h"
#include "shaders/trace_closest_bvh4.spv.h"
#include "shaders/trace_closest_bvh4p.spv.h"
#include "shaders/trace_closest_bvh4q.spv.h"
#include "shaders/trace_closest_bvh4qp.spv.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ripple::bvh {

namespace {

constexpr uint32_t kWorkgroupSizeConstant = 0;  // layout(local_size_x_id = 0) in traverse_bvh4.glsl

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

glm::uvec3 corners(const core::TriangleMesh& mesh, size_t triangle) {
    return mesh.indices.empty() ? glm::uvec3(3 * triangle, 3 * triangle + 1, 3 * triangle + 2) : mesh.indices[triangle];
}

// Kernels read a buffer address even when there is nothing to read: a zero-size buffer has none.
template <class T>
vk::Buffer uploadNonEmpty(const vk::Context& context, const std::vector<T>& items, const std::string& name) {
    vk::Buffer buffer(context, std::max<VkDeviceSize>(16, items.size() * sizeof(T)), name);
    if (!items.empty()) buffer.upload(std::span<const T>(items));
    return buffer;
}

// The packet kernels' needs (traverse_bvh4_packet.glsl): groups of 4 lanes share a load, and every lane
// must take part in each subgroup operation, so no workgroup may end in a partial subgroup.
void checkPacketSupport(const vk::Context& context, uint32_t workgroupSize) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(context.physicalDevice(), &properties);
    const VkSubgroupFeatureFlags needed =
        VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT;
    if ((subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
        (subgroup.supportedOperations & needed) != needed)
        throw std::invalid_argument("Bvh4TraceKernels: packet traversal needs subgroup ballot, arithmetic and "
                                    "vote operations in compute shaders, which " + context.deviceName() +
                                    " lacks");
    if (subgroup.subgroupSize < 4)
        throw std::invalid_argument("Bvh4TraceKernels: packet traversal needs subgroups of at least 4 lanes, not " +
                                    std::to_string(subgroup.subgroupSize));
    if (workgroupSize % subgroup.subgroupSize != 0)
        throw std::invalid_argument("Bvh4TraceKernels: packet traversal needs a workgroup size that is a multiple "
                                    "of the subgroup size " + std::to_string(subgroup.subgroupSize) + ", not " +
                                    std::to_string(workgroupSize));
}

}  // namespace

Bvh4Mesh::Bvh4Mesh(const vk::Context& context, const core::TriangleMesh& mesh, const Bvh4MeshOptions& options)
    : compressed_(options.compressed) {
    const size_t triangleCount = mesh.indices.empty() ? mesh.positions.size() / 3 : mesh.indices.size();
    std::vector<Aabb> boxes(triangleCount);
    for (size_t t = 0; t < triangleCount; ++t) {
        const glm::uvec3 idx = corners(mesh, t);
        for (int c = 0; c < 3; ++c) {
            if (idx[c] >= mesh.positions.size())
                throw std::invalid_argument("Bvh4Mesh: triangle " + std::to_string(t) + " has vertex index " +
                                            std::to_string(idx[c]) + ", past the " +
                                            std::to_string(mesh.positions.size()) + " positions");
            const glm::vec3& p = mesh.positions[idx[c]];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw std::invalid_argument("Bvh4Mesh: vertex " + std::to_string(idx[c]) + " of triangle " +
                                            std::to_string(t) + " is NaN or Inf");
            boxes[t].extend(p);
        }
    }

    const Bvh bvh2 = triangleCount ? buildBinnedSah(boxes, options.build) : Bvh{};
    const auto start = std::chrono::steady_clock::now();
    tree_ = collapseToBvh4(bvh2, options.maxChildren);
    std::vector<gpu::Bvh4CompressedNode> compressedNodes;
    if (compressed_) compressedNodes = compressBvh4(tree_);
    collapseSeconds_ = secondsSince(start);
    nodeCount_ = static_cast<uint32_t>(tree_.nodes.size());

    // Leaf order and the input index in v0.w, exactly as core::Scene lays out a BLAS's triangles.
    std::vector<gpu::TrianglePrim> triangles;
    triangles.reserve(bvh2.primOrder.size());
    for (uint32_t t : bvh2.primOrder) {
        const glm::uvec3 idx = corners(mesh, t);
        triangles.push_back({gpu::vec4(mesh.positions[idx.x], std::bit_cast<float>(t)),
                             gpu::vec4(mesh.positions[idx.y], 0.0f), gpu::vec4(mesh.positions[idx.z], 0.0f)});
    }
    nodes_ = compressed_ ? uploadNonEmpty(context, compressedNodes, "BVH4 compressed nodes")
                         : uploadNonEmpty(context, tree_.nodes, "BVH4 nodes");
    nodeBytes_ = compressed_ ? compressedNodes.size() * sizeof(gpu::Bvh4CompressedNode)
                             : tree_.nodes.size() * sizeof(gpu::Bvh4Node);
    triangles_ = uploadNonEmpty(context, triangles, "BVH4 triangles");
}

Bvh4TraceKernels::Bvh4TraceKernels(const vk::Context& context, uint32_t workgroupSize, uint32_t stepBudget,
                                   Bvh4Traversal traversal)
    : context_(context), workgroupSize_(workgroupSize), stepBudget_(stepBudget) {
    if (stepBudget < 1 || stepBudget > core::kMaxStepBudget)
        throw std::invalid_argument("Bvh4TraceKernels: stepBudget must be in [1, " +
                                    std::to_string(core::kMaxStepBudget) + "], not " + std::to_string(stepBudget));
    const vk::SpecializationConstant constants[] = {{kWorkgroupSizeConstant, workgroupSize}};
    const auto bytes = static_cast<uint32_t>(sizeof(gpu::Bvh4TraceParams));
    if (traversal == Bvh4Traversal::Packet) {
        checkPacketSupport(context, workgroupSize);
        closest_ = vk::ComputePipeline(context, shaders::trace_closest_bvh4p, "trace_closest_bvh4p", bytes, constants);
        any_ = vk::ComputePipeline(context, shaders::trace_any_bvh4p, "trace_any_bvh4p", bytes, constants);
        closestCompressed_ =
            vk::ComputePipeline(context, shaders::trace_closest_bvh4qp, "trace_closest_bvh4qp", bytes, constants);
        anyCompressed_ =
            vk::ComputePipeline(context, shaders::trace_any_bvh4qp, "trace_any_bvh4qp", bytes, constants);
        return;
    }
    closest_ = vk::ComputePipeline(context, shaders::trace_closest_bvh4, "trace_closest_bvh4", bytes, constants);
    any_ = vk::ComputePipeline(context, shaders::trace_any_bvh4, "trace_any_bvh4", bytes, constants);
    closestCompressed_ =
        vk::ComputePipeline(context, shaders::trace_closest_bvh4q, "trace_closest_bvh4q", bytes, constants);
    anyCompressed_ = vk::ComputePipeline(context, shaders::trace_any_bvh4q, "trace_any_bvh4q", bytes, constants);
}

void Bvh4TraceKernels::dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& pipeline, const Bvh4Mesh& mesh,
                                const vk::Buffer& rays, const vk::Buffer& results, VkDeviceSize resultStride,
                                uint32_t rayCount) {
    if (rayCount == 0) return;
    pipeline.bind(cmd);
    const uint64_t maxRaysPerDispatch =
        uint64_t(context_.properties().limits.maxComputeWorkGroupCount[0]) * workgroupSize_;
    for (uint64_t first = 0; first < rayCount; first += maxRaysPerDispatch) {
        const auto count = static_cast<uint32_t>(std::min<uint64_t>(maxRaysPerDispatch, rayCount - first));
        gpu::Bvh4TraceParams params{};
        params.nodes = mesh.nodesAddress();
        params.triangles = mesh.trianglesAddress();
        params.rays = rays.address() + first * sizeof(gpu::Ray);
        params.hits = results.address() + first * resultStride;
        params.rayCount = count;
        params.nodeCount = mesh.nodeCount();
        params.stepBudget = stepBudget_;
        pipeline.pushConstants(cmd, &params, sizeof(params));
        pipeline.dispatch(cmd, (count + workgroupSize_ - 1) / workgroupSize_);
    }
}

const vk::ComputePipeline& Bvh4TraceKernels::closestPipeline(const Bvh4Mesh& mesh) const {
    return mesh.compressed() ? closestCompressed_ : closest_;
}

const vk::ComputePipeline& Bvh4TraceKernels::anyPipeline(const Bvh4Mesh& mesh) const {
    return mesh.compressed() ? anyCompressed_ : any_;
}

void Bvh4TraceKernels::traceClosest(VkCommandBuffer cmd, const Bvh4Mesh& mesh, const vk::Buffer& rays,
                                    const vk::Buffer& hits, uint32_t rayCount) {
    dispatch(cmd, closestPipeline(mesh), mesh, rays, hits, sizeof(gpu::Hit), rayCount);
}

void Bvh4TraceKernels::traceAny(VkCommandBuffer cmd, const Bvh4Mesh& mesh, const vk::Buffer& rays,
                                const vk::Buffer& occluded, uint32_t rayCount) {
    dispatch(cmd, anyPipeline(mesh), mesh, rays, occluded, sizeof(uint32_t), rayCount);
}

template <class Result>
std::vector<Result> Bvh4TraceKernels::traceOnHost(const vk::ComputePipeline& pipeline, const Bvh4Mesh& mesh,
                                                  std::span<const gpu::Ray> rays) {
    std::vector<Result> results(rays.size());
    if (rays.empty()) return results;
    vk::Buffer rayBuffer(context_, rays.size_bytes(), "BVH4 trace rays");
    vk::Buffer resultBuffer(context_, results.size() * sizeof(Result), "BVH4 trace results");
    rayBuffer.upload(rays);
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        dispatch(cmd, pipeline, mesh, rayBuffer, resultBuffer, sizeof(Result), static_cast<uint32_t>(rays.size()));
    });
    resultBuffer.download(std::span(results));
    return results;
}

std::vector<gpu::Hit> Bvh4TraceKernels::traceClosest(const Bvh4Mesh& mesh, std::span<const gpu::Ray> rays) {
    return traceOnHost<gpu::Hit>(closestPipeline(mesh), mesh, rays);
}

std::vector<uint32_t> Bvh4TraceKernels::traceAny(const Bvh4Mesh& mesh, std::span<const gpu::Ray> rays) {
    return traceOnHost<uint32_t>(anyPipeline(mesh), mesh, rays);
}

}  // namespace ripple::bvh
