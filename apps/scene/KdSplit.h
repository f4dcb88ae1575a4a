// The k-d split the data-parallel tools deal regions of a field with (AmrPartition.h, NanoVdbPartition.h): a box
// of integer coordinates halved along its longest axis, again and again, each cut placed where the weight on
// its low side best matches the low side's share of the ranks.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>

namespace ripple::apps {

// A box of integer coordinates [lo, hi]: the two sides of a cut at c are [lo, c] and [c, hi] (whether they
// share the plane c is the caller's reading: cells between planes, or voxels on them).
struct KdBox {
    glm::i64vec3 lo{0}, hi{0};
};

// `rank`'s region of `whole` split among `ranks`. weight(box) is what a box holds (cells, active voxels). Cuts
// are tried at up to 256 planes strictly inside a box. Throws std::runtime_error when a box to split is less
// than 2 along every axis.
KdBox kdRegion(const KdBox& whole, uint32_t rank, uint32_t ranks, const std::function<double(const KdBox&)>& weight);

}  // namespace ripple::apps
