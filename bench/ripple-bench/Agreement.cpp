// Ray-by-ray comparison of two tracers' results (reference: Embree; test: Ripple).
#include "bench/ripple-bench/Agreement.h"

#include <algorithm>
#include <cmath>

namespace ripple::bench {

namespace {

constexpr uint32_t kFlags = ~0xffu;

bool found(uint32_t status) { return (status & 0xffu) == gpu::HIT_FOUND; }

}  // namespace

Agreement compareClosest(std::span<const gpu::Hit> reference, std::span<const gpu::Hit> test) {
    Agreement a;
    a.rays = std::min(reference.size(), test.size());
    for (size_t i = 0; i < a.rays; ++i) {
        const gpu::Hit& r = reference[i];
        const gpu::Hit& t = test[i];
        const bool refHit = found(r.status);
        const bool testHit = found(t.status);
        a.referenceHits += refHit;
        a.testHits += testHit;
        if (t.status & kFlags) {
            ++a.flagged;
            continue;
        }
        if (!refHit && !testHit) {
            ++a.agree;
        } else if (refHit && testHit) {
            if (r.primId == t.primId) {
                ++a.agree;
            } else if (std::abs(r.t - t.t) <= kTieRelative * std::max(std::abs(r.t), std::abs(t.t))) {
                ++a.agree;
                ++a.ties;
            }
        }
    }
    return a;
}

Agreement compareAny(std::span<const uint32_t> reference, std::span<const uint32_t> test) {
    Agreement a;
    a.rays = std::min(reference.size(), test.size());
    for (size_t i = 0; i < a.rays; ++i) {
        const bool refHit = found(reference[i]);
        const bool testHit = found(test[i]);
        a.referenceHits += refHit;
        a.testHits += testHit;
        if (test[i] & kFlags) {
            ++a.flagged;
            continue;
        }
        a.agree += refHit == testHit;
    }
    return a;
}

}  // namespace ripple::bench
