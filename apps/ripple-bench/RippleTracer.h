// Ripple's side of ripple-bench: one Vulkan context and kernel set for the whole run, one core::Scene per
// benchmark scene, and the two ways to trace a ray set (host convenience call, device-side launch).
#pragma once

#include "apps/ripple-bench/Timing.h"
#include "core/render/TraceKernels.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/Context.h"
#include "core/vk/Timestamps.h"

#include <memory>
#include <span>
#include <vector>

namespace ripple::bench {

class RippleTracer {
public:
    explicit RippleTracer(const core::TraceOptions& options);

    const std::string& deviceName() const { return context_.deviceName(); }

    // One mesh, one identity instance. Returns the time of the core::Scene construction (validation, BVH
    // builds, upload); report().blasBuildSeconds is the BVH part of it.
    Sample build(const core::TriangleMesh& mesh);
    const core::SceneReport& report() const { return scene_->report(); }

    // Host convenience: upload, trace, wait, download.
    std::vector<gpu::Hit> traceClosest(std::span<const gpu::Ray> rays);
    std::vector<uint32_t> traceAny(std::span<const gpu::Ray> rays);

    // Device-side: stage() uploads the rays and sizes the results once; each launch() is then one
    // submitAndWait around the kernel, with wall and process CPU time around it and GPU time from
    // timestamps at both ends of the command buffer.
    void stage(std::span<const gpu::Ray> rays, bool anyHit);
    Sample launch();
    std::vector<gpu::Hit> downloadHits() const;
    std::vector<uint32_t> downloadOccluded() const;

private:
    vk::Context context_;
    core::TraceKernels kernels_;
    vk::Timestamps timestamps_;
    std::unique_ptr<core::Scene> scene_;
    vk::Buffer rays_, results_;
    uint32_t stagedCount_ = 0;
    bool stagedAnyHit_ = false;
};

}  // namespace ripple::bench
