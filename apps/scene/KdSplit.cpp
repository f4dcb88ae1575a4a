// The k-d split of a box among ranks (see KdSplit.h).
#include "apps/scene/KdSplit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ripple::apps {

KdBox kdRegion(const KdBox& whole, uint32_t rank, uint32_t ranks, const std::function<double(const KdBox&)>& weight) {
    KdBox region = whole;
    uint32_t first = 0, count = ranks;
    while (count > 1) {
        const glm::i64vec3 extent = region.hi - region.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        if (extent[axis] < 2)
            throw std::runtime_error("a region of " + std::to_string(extent.x) + "x" + std::to_string(extent.y) + "x" +
                                     std::to_string(extent.z) + " cannot be split among " + std::to_string(count) + " ranks");
        const uint32_t lowRanks = count / 2;
        const double target = weight(region) * double(lowRanks) / double(count);
        const int64_t step = std::max<int64_t>(1, extent[axis] / 256);
        int64_t bestCut = region.lo[axis] + extent[axis] / 2;
        double bestMiss = INFINITY;
        for (int64_t cut = region.lo[axis] + 1; cut < region.hi[axis]; cut += step) {
            KdBox low = region;
            low.hi[axis] = cut;
            const double miss = std::abs(weight(low) - target);
            if (miss < bestMiss) {
                bestMiss = miss;
                bestCut = cut;
            }
        }
        if (rank < first + lowRanks) {
            region.hi[axis] = bestCut;
            count = lowRanks;
        } else {
            region.lo[axis] = bestCut;
            first += lowRanks;
            count -= lowRanks;
        }
    }
    return region;
}

}  // namespace ripple::apps
