// Collapse of a binned-SAH BVH2 into the 4-wide layout of shaders/shared/bvh4.h, the layout every kernel
// traverses. Leaves and the leaf-ordered primitive array stay exactly those of the BVH2.
#pragma once

#include "core/bvh/BinnedSahBuilder.h"
#include "shaders/shared/bvh4.h"

#include <vector>

namespace ripple::bvh {

struct Bvh4 {
    std::vector<gpu::Bvh4Node> nodes;  // nodes[0] is the root; empty when the BVH2 is
    uint32_t depth = 0;                // deepest leaf (root = 1); never above the BVH2's
    uint32_t leafCount = 0;
    uint32_t childSlotsUsed = 0;       // over all nodes: 4 * nodes.size() when every node is full
};

// SAH-greedy collapse: each BVH4 node starts from a BVH2 node's two children and, while it has fewer than
// four, replaces its inner child of largest surface area by that child's two children (the child most
// likely to be entered is the one whose node fetch is most worth saving). Boxes are copied, never
// recomputed, so every child box holds its subtree exactly as in the BVH2. Throws std::invalid_argument
// when a leaf does not fit a child word (more than 8 primitives, or a last slot of 2^28 or more).
// maxChildren 2 gives the BVH2 itself in this layout (one node per BVH2 node): the control that separates
// the effect of width from that of the layout and the single-level kernel.
Bvh4 collapseToBvh4(const Bvh& bvh2, uint32_t maxChildren = 4);

}  // namespace ripple::bvh
