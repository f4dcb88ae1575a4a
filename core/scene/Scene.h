// The flat GPU scene: validates a SceneDescription (skipping and counting bad primitives), builds a BLAS
// per mesh or sphere set and a TLAS over instances, and uploads everything the trace kernels read.
#pragma once

#include "core/bvh/BinnedSahBuilder.h"
#include "core/scene/SceneDescription.h"
#include "core/vk/Buffer.h"
#include "shaders/shared/scene.h"

#include <string>
#include <vector>

namespace ripple::core {

// What validation dropped, and why; nothing bad ever reaches a kernel.
struct SceneReport {
    uint64_t trianglesKept = 0;
    uint64_t trianglesSkipped = 0;     // NaN/Inf vertex, index out of range, or zero area
    uint64_t spheresKept = 0;
    uint64_t spheresSkipped = 0;       // NaN/Inf center, radius <= 0 or non-finite
    uint64_t instancesKept = 0;
    uint64_t instancesSkipped = 0;     // empty geometry, bad reference, or non-finite/singular transform
    double blasBuildSeconds = 0.0;
    double tlasBuildSeconds = 0.0;
    uint64_t gpuBytes = 0;
    std::vector<std::string> messages; // one line per kind of problem per geometry, naming it
};

class Scene {
public:
    Scene(const vk::Context& context, const SceneDescription& description,
          const bvh::BuildOptions& buildOptions = {});

    const SceneReport& report() const { return report_; }
    VkDeviceAddress descAddress() const { return desc_.address(); }
    uint32_t instanceCount() const { return instanceCount_; }
    const bvh::Aabb& bounds() const { return bounds_; }

private:
    SceneReport report_;
    bvh::Aabb bounds_;
    uint32_t instanceCount_ = 0;
    vk::Buffer nodes_, triangles_, spheres_, instances_, desc_;
};

}  // namespace ripple::core
