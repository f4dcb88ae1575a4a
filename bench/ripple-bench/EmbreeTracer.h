// The reference tracer of ripple-bench: Embree 3 (default scene flags, medium build quality) tracing the same
// gpu::Ray arrays as Ripple, one rtcIntersect1/rtcOccluded1 per ray in a oneTBB parallel loop.
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/ray.h"

#include <embree3/rtcore.h>

#include <span>
#include <string>

namespace ripple::bench {

class EmbreeTracer {
public:
    EmbreeTracer();
    ~EmbreeTracer();
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    // Replaces the current scene: rtcNewScene, one triangle geometry (geomID 0, primID = triangle index in
    // `mesh`, as Ripple numbers them), rtcCommitScene. Throws std::runtime_error on any Embree error.
    void build(const core::TriangleMesh& mesh);

    // Results go to caller-owned arrays so that timed runs allocate nothing. Hit.instanceId is 0 on a hit,
    // matching the single identity instance Ripple traces.
    void traceClosest(std::span<const gpu::Ray> rays, std::span<gpu::Hit> hits) const;
    void traceAny(std::span<const gpu::Ray> rays, std::span<uint32_t> occluded) const;

    static std::string version();

private:
    void releaseScene();
    void throwOnError(const char* what) const;

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

}  // namespace ripple::bench
