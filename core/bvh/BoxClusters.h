// Few boxes that cover many: what a data-parallel rank tells the others about where its part of the scene
// lies (core::Scene::regions(), mpi/BoundsExchange). Boxes are ordered along a Morton curve through their
// centres and cut into at most `maxCount` runs of consecutive boxes; each run's union is one cluster, so
// nearby boxes share a cluster and the clusters stay tight where the boxes are spread out.
#pragma once

#include "core/bvh/Aabb.h"

#include <cstddef>
#include <span>
#include <vector>

namespace ripple::bvh {

// Every non-empty input box lies inside some output box; empty input boxes are dropped. Deterministic.
std::vector<Aabb> clusterBoxes(std::span<const Aabb> boxes, size_t maxCount);

}  // namespace ripple::bvh
