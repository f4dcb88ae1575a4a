// How often Ripple's answers match Embree's on the same rays: the benchmark's correctness column.
#pragma once

#include "shaders/shared/ray.h"

#include <cstdint>
#include <span>

namespace ripple::bench {

// Hit distances within this relative difference count as the same surface point.
inline constexpr float kTieRelative = 1e-4f;

struct Agreement {
    uint64_t rays = 0;
    uint64_t agree = 0;    // includes ties
    uint64_t ties = 0;     // closest-hit only: different primitive at the same t (shared edges, overlaps)
    uint64_t flagged = 0;  // Ripple answers with HIT_FLAG_* set: never trustworthy, counted as disagreement
    uint64_t referenceHits = 0;  // Embree's hit (closest) or occluded (any-hit) count, for scale
    uint64_t testHits = 0;
    double percent() const { return rays ? 100.0 * double(agree) / double(rays) : 100.0; }
};

// Closest-hit: agree when both miss, both hit the same primitive, or both hit at t within kTieRelative.
Agreement compareClosest(std::span<const gpu::Hit> reference, std::span<const gpu::Hit> test);
// Any-hit: agree when the occlusion booleans match.
Agreement compareAny(std::span<const uint32_t> reference, std::span<const uint32_t> test);

}  // namespace ripple::bench
