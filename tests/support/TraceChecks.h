// GPU traversal checked against the reference, with doctest assertions: what the traversal and
// cylinder suites share. Header-only, like TestContext.h, because it asserts inside the test executable.
#pragma once

#include "core/render/TraceKernels.h"
#include "core/scene/Scene.h"
#include "tests/support/HitAgreement.h"
#include "tests/support/ReferenceTracer.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <span>
#include <vector>

namespace ripple::test {

struct TraceResults {
    std::vector<gpu::Hit> closest;
    std::vector<uint32_t> any;
};

inline TraceResults traceOnGpu(const core::SceneDescription& description, std::span<const gpu::Ray> rays,
                               const core::TraceOptions& options = {}) {
    core::Scene scene(testContext(), description);
    core::TraceKernels kernels(testContext(), options);
    return {kernels.traceClosest(scene, rays), kernels.traceAny(scene, rays)};
}

// No wrong and no flagged closest hit, at least `minExactOrTie` of rays exact or tied (the rest edge
// cases), and any-hit answers equal to the reference's except on those edge rays.
inline Agreement checkAgainstReference(const core::SceneDescription& description, std::span<const gpu::Ray> rays,
                                double minExactOrTie = 0.999) {
    ValidationGuard guard;
    const TraceResults gpuResults = traceOnGpu(description, rays);
    const std::vector<RefHit> ref = traceClosestAll(description, rays);
    const Agreement a = compareClosest(description, rays, gpuResults.closest, ref);
    INFO("exact " << a.exact << ", ties " << a.ties << ", edges " << a.edges << ", wrong " << a.wrong << ", flagged " << a.flagged);
    CHECK(a.wrong == 0);
    CHECK(a.flagged == 0);
    CHECK(a.exactOrTie() >= minExactOrTie);
    uint64_t anyMismatch = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        anyMismatch += (gpuResults.any[i] == gpu::HIT_FOUND) != ref[i].found;
    CHECK(anyMismatch <= a.edges);
    return a;
}

}  // namespace ripple::test
