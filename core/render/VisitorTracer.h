// The RankTracer of the wavefront path tracer: traces rays visiting from other ranks against this rank's
// part of the scene, and where it finds a closer hit runs pt_surface on it, so the ray carries home the
// record of the closest hit so far. Where this rank has volumes it samples free flight through them up to
// that hit (pt_volume: a nearer collision becomes the record) and multiplies shadow rays' transmittance by
// theirs (pt_shadow_volume). Buffers grow with the largest batch seen and are kept between hops; visits
// beyond one dispatch's worth (maxComputeWorkGroupCount workgroups) are traced in batches of that many.
#pragma once

#include "core/render/RayExchange.h"
#include "core/render/TraceKernels.h"
#include "core/render/VolumeParking.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"

namespace ripple::core {

class VisitorTracer final : public RankTracer {
public:
    VisitorTracer(const vk::Context& context, TraceKernels& trace, uint32_t workgroupSize);

    // This rank's volume stages and what keys their random numbers; freeFlight null: no volumes here.
    struct Volumes {
        const vk::ComputePipeline* freeFlight = nullptr;     // pt_volume
        const vk::ComputePipeline* transmittance = nullptr;  // pt_shadow_volume
        VolumeParking* parking = nullptr;                    // their resume rounds
        uint32_t bounce = 0;
        uint32_t sampleIndex = 0;
        uint32_t rank = 0;
    };

    // The scene, frame constants and pt_surface pipeline (the variant for this scene) the next visits use,
    // and the volume stages, set before each exchange.
    void use(const Scene& scene, VkDeviceAddress frameConstants, const vk::ComputePipeline& surface,
             const Volumes& volumes);

    void traceClosest(std::span<WireRay> rays) override;
    void traceShadow(std::span<WireShadowRay> rays) override;

private:
    // The most rays one batch takes: every stage of it is one dispatch, also the trace kernels' (in their
    // own workgroup size) and the volume stages' resume rounds, sized by the kernels from the batch.
    size_t batchLimit() const;
    void traceClosestBatch(std::span<WireRay> rays);
    void traceShadowBatch(std::span<WireShadowRay> rays);
    void reserve(size_t count);
    gpu::StageParams volumeParams() const;
    // Records one path stage over `count` items with these parameters (their count set to it).
    void dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p, uint32_t count) const;
    // The same for a volume stage, with the resume rounds of the marches it parks.
    void dispatchVolumeStage(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p,
                             uint32_t count) const;

    const vk::Context& context_;
    TraceKernels& trace_;
    const vk::ComputePipeline* surface_ = nullptr;
    uint32_t workgroupSize_;
    const Scene* scene_ = nullptr;
    VkDeviceAddress frame_ = 0;
    Volumes volumes_;
    size_t capacity_ = 0;
    vk::Buffer rays_, hits_, surfaces_, occlusion_, transmittance_;
    std::vector<gpu::Ray> hostRays_;
    std::vector<gpu::SurfaceRecord> hostRecords_;
    std::vector<uint32_t> hostOcclusion_, pending_;
    std::vector<float> hostTransmittance_;
};

}  // namespace ripple::core
