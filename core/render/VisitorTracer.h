// The RankTracer of the wavefront path tracer: traces rays visiting from other ranks against this rank's
// part of the scene, and where it finds a closer hit runs pt_surface on it, so the ray carries home the
// record of the closest hit so far. Buffers grow with the largest batch seen and are kept between hops.
#pragma once

#include "core/render/RayExchange.h"
#include "core/render/TraceKernels.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"

namespace ripple::core {

class VisitorTracer final : public RankTracer {
public:
    VisitorTracer(const vk::Context& context, TraceKernels& trace, uint32_t workgroupSize);

    // The scene, frame constants and pt_surface pipeline (the variant for this scene) the next visits use,
    // set before each exchange.
    void use(const Scene& scene, VkDeviceAddress frameConstants, const vk::ComputePipeline& surface);

    void traceClosest(std::span<WireRay> rays) override;
    void traceShadow(std::span<WireShadowRay> rays) override;

private:
    void reserve(size_t count);

    const vk::Context& context_;
    TraceKernels& trace_;
    const vk::ComputePipeline* surface_ = nullptr;
    uint32_t workgroupSize_;
    const Scene* scene_ = nullptr;
    VkDeviceAddress frame_ = 0;
    size_t capacity_ = 0;
    vk::Buffer rays_, hits_, surfaces_, occlusion_;
    std::vector<gpu::Ray> hostRays_;
    std::vector<gpu::SurfaceRecord> hostRecords_;
    std::vector<uint32_t> hostOcclusion_, pending_;
};

}  // namespace ripple::core
