// Few boxes that cover many: what a data-parallel rank tells the others about where its part of the scene
// lies (core::Scene::regions(), mpi/BoundsExchange). The boxes are split recursively at the median of
// their centres along the widest axis (a k-d split) into at most `maxCount` groups of nearly equal size;
// each group's union is one cluster. Clusters come out in the split's leaf order, so consecutive clusters
// are siblings and lie near each other.
#pragma once

#include "core/bvh/Aabb.h"

#include <cstddef>
#include <span>
#include <vector>

namespace ripple::bvh {

// Every non-empty input box lies inside some output box; empty input boxes are dropped; min(maxCount,
// non-empty boxes) clusters. Deterministic.
std::vector<Aabb> clusterBoxes(std::span<const Aabb> boxes, size_t maxCount);

}  // namespace ripple::bvh
