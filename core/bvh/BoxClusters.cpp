// Median-split clustering of boxes (see BoxClusters.h).
#include "core/bvh/BoxClusters.h"

#include <algorithm>

namespace ripple::bvh {

namespace {

// Splits boxes[first, last) into `count` clusters appended to `out`, in leaf order.
void split(std::vector<Aabb>& boxes, size_t first, size_t last, size_t count, std::vector<Aabb>& out) {
    if (count <= 1) {
        Aabb cluster;
        for (size_t i = first; i < last; ++i) cluster.extend(boxes[i]);
        out.push_back(cluster);
        return;
    }
    Aabb centres;
    for (size_t i = first; i < last; ++i) centres.extend(boxes[i].center());
    const glm::vec3 extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const size_t leftCount = count / 2;
    const size_t middle = first + (last - first) * leftCount / count;  // boxes in proportion to clusters
    std::nth_element(boxes.begin() + long(first), boxes.begin() + long(middle), boxes.begin() + long(last),
                     [axis](const Aabb& a, const Aabb& b) { return a.center()[axis] < b.center()[axis]; });
    split(boxes, first, middle, leftCount, out);
    split(boxes, middle, last, count - leftCount, out);
}

}  // namespace

std::vector<Aabb> clusterBoxes(std::span<const Aabb> boxes, size_t maxCount) {
    std::vector<Aabb> kept;
    for (const Aabb& box : boxes)
        if (!box.empty()) kept.push_back(box);
    std::vector<Aabb> clusters;
    if (maxCount == 0 || kept.empty()) return clusters;
    split(kept, 0, kept.size(), std::min(maxCount, kept.size()), clusters);
    return clusters;
}

}  // namespace ripple::bvh
