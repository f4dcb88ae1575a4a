// Agreement of GPU closest hits with the double-precision reference tracer: each ray classified as
// exact, tie, edge case or wrong, with tolerances derived from float's resolution at the hit.
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/ray.h"
#include "tests/support/ReferenceTracer.h"

#include <cstdint>
#include <span>

namespace ripple::test {

// Agreement of GPU hits with the double-precision reference. Per ray, with scale = the largest
// coordinate magnitude of the ray origin and hit point (at least 1), cos = |n.d| / |d| at the hit, and
// kappa = (longest edge)^2 / (2 area) the conditioning of a triangle (1 for spheres and cylinders):
//  - exact: same primitive, and t within tT = 1e-6 * scale * kappa / (|d| * max(cos, 1e-3)): float
//    positions are off by ~1e-7 * scale, which moves t by that over cos along the ray, and by kappa
//    more on thin triangles, whose plane float pins down poorly;
//  - tie: another primitive at the reference t (within tT), or the reference itself saw several there;
//  - edge: hit/miss or primitive differs, and the ray passes within 4e-6 * scale of an edge of the
//    primitive in question (the reference's or the GPU's), of a sphere's or cylinder's silhouette, or
//    of a cylinder's end rim: float cannot resolve which side such a ray passes (needles narrower than
//    that are all edge);
//  - wrong: anything else. Tests require no wrong ray and state how many may be ties or edges.
struct Agreement {
    uint64_t exact = 0, ties = 0, edges = 0, wrong = 0, flagged = 0;
    uint64_t total() const { return exact + ties + edges + wrong + flagged; }
    double exactOrTie() const { return total() == 0 ? 1.0 : double(exact + ties) / double(total()); }
};

Agreement compareClosest(const core::SceneDescription& d, std::span<const gpu::Ray> rays,
                         std::span<const gpu::Hit> gpuHits, std::span<const RefHit> ref);

}  // namespace ripple::test
