// Visiting rays (see VisitorTracer.h): closest hits are traced with tmax clipped to the best t so far, so
// a hit found here is always closer, and only then does its record replace the one the ray carries.
// Shadow rays already occluded elsewhere are not traced again.
#include "core/render/VisitorTracer.h"

#include "shaders/shared/path.h"

#include <algorithm>

namespace ripple::core {

namespace {

void hostReadBarrier(VkCommandBuffer cmd) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
}

}  // namespace

VisitorTracer::VisitorTracer(const vk::Context& context, TraceKernels& trace, uint32_t workgroupSize)
    : context_(context), trace_(trace), workgroupSize_(workgroupSize) {}

void VisitorTracer::use(const Scene& scene, VkDeviceAddress frameConstants, const vk::ComputePipeline& surface,
                        const Volumes& volumes) {
    scene_ = &scene;
    frame_ = frameConstants;
    surface_ = &surface;
    volumes_ = volumes;
}

gpu::StageParams VisitorTracer::volumeParams() const {
    gpu::StageParams p{};
    p.frame = frame_;
    p.scene = scene_->descAddress();
    p.bounce = volumes_.bounce;
    p.sampleIndex = volumes_.sampleIndex;
    p.mode = volumes_.rank + 1;  // keys this rank's random numbers apart from the home rank's
    return p;
}

void VisitorTracer::dispatch(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p,
                             uint32_t count) const {
    p.count = count;
    stage.bind(cmd);
    stage.pushConstants(cmd, &p, sizeof(p));
    stage.dispatch(cmd, (count + workgroupSize_ - 1) / workgroupSize_);
}

void VisitorTracer::dispatchVolumeStage(VkCommandBuffer cmd, const vk::ComputePipeline& stage, gpu::StageParams p,
                                        uint32_t count) const {
    p.count = count;
    volumes_.parking->run(cmd, stage, p, count, {count, nullptr, 0, workgroupSize_});
}

void VisitorTracer::reserve(size_t count) {
    if (count <= capacity_) return;
    capacity_ = std::max(count, capacity_ * 2);
    rays_ = vk::Buffer(context_, capacity_ * sizeof(gpu::Ray), "visiting rays");
    hits_ = vk::Buffer(context_, capacity_ * sizeof(gpu::Hit), "visiting hits");
    surfaces_ = vk::Buffer(context_, capacity_ * sizeof(gpu::SurfaceRecord), "visiting surface records");
    occlusion_ = vk::Buffer(context_, capacity_ * sizeof(uint32_t), "visiting occlusion");
    transmittance_ = vk::Buffer(context_, capacity_ * sizeof(float), "visiting transmittance");
}

size_t VisitorTracer::batchLimit() const {
    return size_t(context_.properties().limits.maxComputeWorkGroupCount[0]) *
           std::min(workgroupSize_, trace_.options().workgroupSize);
}

void VisitorTracer::traceClosest(std::span<WireRay> rays) {
    for (size_t first = 0; first < rays.size(); first += batchLimit())
        traceClosestBatch(rays.subspan(first, std::min(batchLimit(), rays.size() - first)));
}

void VisitorTracer::traceShadow(std::span<WireShadowRay> rays) {
    for (size_t first = 0; first < rays.size(); first += batchLimit())
        traceShadowBatch(rays.subspan(first, std::min(batchLimit(), rays.size() - first)));
}

void VisitorTracer::traceClosestBatch(std::span<WireRay> rays) {
    if (rays.empty() || !scene_ || !surface_) return;
    reserve(rays.size());
    hostRays_.resize(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        hostRays_[i] = rays[i].ray;
        if (rays[i].record.status == gpu::HIT_FOUND) hostRays_[i].direction.w = rays[i].record.position.w;
    }
    rays_.upload(hostRays_.data(), hostRays_.size() * sizeof(gpu::Ray));
    const auto count = static_cast<uint32_t>(rays.size());
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        trace_.traceClosest(cmd, *scene_, rays_, hits_, count);
        vk::computeBarrier(cmd);
        gpu::StageParams p{};
        p.frame = frame_;
        p.scene = scene_->descAddress();
        p.rays = rays_.address();
        p.hits = hits_.address();
        p.surfaces = surfaces_.address();
        dispatch(cmd, *surface_, p, count);
        if (volumes_.freeFlight) {  // a collision in this rank's volumes before its own hit replaces it
            vk::computeBarrier(cmd);
            gpu::StageParams v = volumeParams();
            v.rays = rays_.address();
            v.surfaces = surfaces_.address();
            dispatchVolumeStage(cmd, *volumes_.freeFlight, v, count);
        }
        hostReadBarrier(cmd);
    });
    hostRecords_.resize(rays.size());
    surfaces_.download(hostRecords_.data(), hostRecords_.size() * sizeof(gpu::SurfaceRecord));
    for (size_t i = 0; i < rays.size(); ++i) {
        const gpu::SurfaceRecord& found = hostRecords_[i];
        gpu::SurfaceRecord& carried = rays[i].record;
        if (found.status == gpu::HIT_FOUND) takeCloserHit(carried, found);
        else carried.status |= found.status & kHitStatusFlags;
    }
}

void VisitorTracer::traceShadowBatch(std::span<WireShadowRay> rays) {
    if (rays.empty() || !scene_) return;
    pending_.clear();
    hostRays_.clear();
    for (size_t i = 0; i < rays.size(); ++i) {
        if ((rays[i].occlusion & 0xFFu) == gpu::HIT_FOUND) continue;
        pending_.push_back(static_cast<uint32_t>(i));
        hostRays_.push_back(rays[i].ray);
    }
    if (pending_.empty()) return;
    reserve(pending_.size());
    rays_.upload(hostRays_.data(), hostRays_.size() * sizeof(gpu::Ray));
    const auto count = static_cast<uint32_t>(pending_.size());
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        trace_.traceAny(cmd, *scene_, rays_, occlusion_, count);
        hostReadBarrier(cmd);
    });
    hostOcclusion_.resize(count);
    occlusion_.download(hostOcclusion_.data(), count * sizeof(uint32_t));
    for (uint32_t k = 0; k < count; ++k) {
        uint32_t& carried = rays[pending_[k]].occlusion;
        carried = mergeOcclusion(carried, hostOcclusion_[k]);
    }
    if (!volumes_.transmittance) return;
    // This rank's volumes dim what is still unoccluded (the rays are still in rays_, in pending_ order).
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        gpu::StageParams v = volumeParams();
        v.shadowRays = rays_.address();
        v.results = transmittance_.address();
        dispatchVolumeStage(cmd, *volumes_.transmittance, v, count);
        hostReadBarrier(cmd);
    });
    hostTransmittance_.resize(count);
    transmittance_.download(hostTransmittance_.data(), count * sizeof(float));
    for (uint32_t k = 0; k < count; ++k) rays[pending_[k]].transmittance *= hostTransmittance_[k];
}

}  // namespace ripple::core
