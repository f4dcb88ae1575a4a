// Morton-order clustering of boxes (see BoxClusters.h).
#include "core/bvh/BoxClusters.h"

#include <algorithm>
#include <cstdint>

namespace ripple::bvh {

namespace {

// 10 bits of x spread to every third bit.
uint32_t spreadBits(uint32_t x) {
    x &= 0x3FFu;
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

}  // namespace

std::vector<Aabb> clusterBoxes(std::span<const Aabb> boxes, size_t maxCount) {
    std::vector<Aabb> kept;
    Aabb all;
    for (const Aabb& box : boxes)
        if (!box.empty()) {
            kept.push_back(box);
            all.extend(box);
        }
    if (kept.size() <= maxCount || maxCount == 0) return maxCount == 0 ? std::vector<Aabb>{} : kept;

    const glm::vec3 extent = glm::max(all.hi - all.lo, glm::vec3(1e-30f));
    std::vector<std::pair<uint32_t, uint32_t>> order(kept.size());  // (Morton code of the centre, index)
    for (size_t i = 0; i < kept.size(); ++i) {
        const glm::vec3 unit = glm::clamp((kept[i].center() - all.lo) / extent, 0.0f, 1.0f);
        const glm::uvec3 cell = glm::uvec3(unit * 1023.0f);
        order[i] = {spreadBits(cell.x) | (spreadBits(cell.y) << 1) | (spreadBits(cell.z) << 2), uint32_t(i)};
    }
    std::sort(order.begin(), order.end());
    std::vector<Aabb> clusters(maxCount);
    for (size_t k = 0; k < order.size(); ++k) clusters[k * maxCount / order.size()].extend(kept[order[k].second]);
    return clusters;
}

}  // namespace ripple::bvh
