// Ripple scene construction and trace launches as ripple-bench times them.
#include "apps/ripple-bench/RippleTracer.h"

#include <stdexcept>

namespace ripple::bench {

namespace {

vk::ContextOptions quietContext() {
    vk::ContextOptions options;
    options.printDeviceChoice = false;  // stdout carries only the tables; main names the device on stderr
    return options;
}

}  // namespace

RippleTracer::RippleTracer(const core::TraceOptions& options)
    : context_(quietContext()), kernels_(context_, options), timestamps_(context_, 2) {}

Sample RippleTracer::build(const core::TriangleMesh& mesh) {
    scene_.reset();  // free the previous scene's GPU memory before allocating the next
    rays_ = {};
    results_ = {};
    core::SceneDescription description;
    description.meshes.push_back(mesh);  // copied outside the timed part
    description.instances.push_back(core::InstanceDescription{});
    return measure([&] { scene_ = std::make_unique<core::Scene>(context_, description); });
}

std::vector<gpu::Hit> RippleTracer::traceClosest(std::span<const gpu::Ray> rays) {
    return kernels_.traceClosest(*scene_, rays);
}

std::vector<uint32_t> RippleTracer::traceAny(std::span<const gpu::Ray> rays) {
    return kernels_.traceAny(*scene_, rays);
}

void RippleTracer::stage(std::span<const gpu::Ray> rays, bool anyHit) {
    if (rays.empty()) throw std::logic_error("RippleTracer::stage: no rays");
    rays_ = {};
    results_ = {};
    rays_ = vk::Buffer(context_, rays.size_bytes(), "bench rays");
    rays_.upload(rays);
    const size_t resultBytes = anyHit ? sizeof(uint32_t) : sizeof(gpu::Hit);
    results_ = vk::Buffer(context_, rays.size() * resultBytes, anyHit ? "bench occlusion" : "bench hits");
    stagedCount_ = uint32_t(rays.size());
    stagedAnyHit_ = anyHit;
}

Sample RippleTracer::launch() {
    Sample s = measure([&] {
        context_.submitAndWait([&](VkCommandBuffer cmd) {
            timestamps_.reset(cmd);
            timestamps_.write(cmd, 0);
            if (stagedAnyHit_) kernels_.traceAny(cmd, *scene_, rays_, results_, stagedCount_);
            else kernels_.traceClosest(cmd, *scene_, rays_, results_, stagedCount_);
            timestamps_.write(cmd, 1);
        });
    });
    s.gpu = timestamps_.seconds(0, 1);
    return s;
}

std::vector<gpu::Hit> RippleTracer::downloadHits() const {
    std::vector<gpu::Hit> hits(stagedAnyHit_ ? 0 : stagedCount_);
    results_.download(std::span<gpu::Hit>(hits));
    return hits;
}

std::vector<uint32_t> RippleTracer::downloadOccluded() const {
    std::vector<uint32_t> occluded(stagedAnyHit_ ? stagedCount_ : 0);
    results_.download(std::span<uint32_t>(occluded));
    return occluded;
}

}  // namespace ripple::bench
