// BVH2 -> BVH4 collapse (see Bvh4Collapse.h): one recursive pass over the BVH2, depth bounded by its depth.
#include "core/bvh/Bvh4Collapse.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>
#include <string>

namespace ripple::bvh {

namespace {

struct Child {
    Aabb box;
    uint32_t reference = 0;
    uint32_t count = 0;
    bool inner() const { return count == 0; }
};

// A node's children while it is being widened: at most 4 (below 4, one inner child gives way to its two).
struct Children {
    std::array<Child, 4> items;
    size_t size = 0;
    Child* begin() { return items.data(); }
    Child* end() { return items.data() + size; }
    void erase(Child* at) {
        std::move(at + 1, end(), at);
        --size;
    }
};

// The BVH2 children of a node, leaving out the empty one a single-leaf BVH has.
void appendChildren(const gpu::BvhNode& node, Children& out) {
    const gpu::vec4* sides[2][2] = {{&node.leftMin, &node.leftMax}, {&node.rightMin, &node.rightMax}};
    for (const auto& side : sides) {
        const Child c{Aabb{glm::vec3(*side[0]), glm::vec3(*side[1])}, std::bit_cast<uint32_t>(side[0]->w),
                      std::bit_cast<uint32_t>(side[1]->w)};
        if (c.count == 0 && c.reference == 0) continue;
        out.items[out.size++] = c;
    }
}

uint32_t leafWord(const Child& leaf) {
    if (leaf.count > 8 || uint64_t(leaf.reference) + leaf.count - 1 > gpu::BVH4_MAX_LEAF_FIRST)
        throw std::invalid_argument("collapseToBvh4: leaf of " + std::to_string(leaf.count) + " primitives at slot " +
                                    std::to_string(leaf.reference) + " does not fit a BVH4 child word (at most 8, "
                                    "last slot below 2^28)");
    return gpu::BVH4_LEAF_BIT | (leaf.reference << 3) | (leaf.count - 1);
}

class Collapser {
public:
    Collapser(const Bvh& bvh2, uint32_t maxChildren, Bvh4& out) : bvh2_(bvh2), maxChildren_(maxChildren), out_(out) {}

    // Emits the BVH4 node standing for BVH2 node `node2` and its subtree; returns its index.
    uint32_t emit(uint32_t node2, uint32_t depth) {
        if (node2 >= bvh2_.nodes.size())
            throw std::invalid_argument("collapseToBvh4: child node " + std::to_string(node2) + " out of range");
        const auto index = static_cast<uint32_t>(out_.nodes.size());
        out_.nodes.emplace_back();
        out_.depth = std::max(out_.depth, depth);

        Children children;
        appendChildren(bvh2_.nodes[node2], children);
        while (children.size < maxChildren_) {
            auto widest = children.end();
            for (auto it = children.begin(); it != children.end(); ++it)
                if (it->inner() && (widest == children.end() || it->box.halfArea() > widest->box.halfArea()))
                    widest = it;
            if (widest == children.end()) break;  // only leaves left
            const uint32_t pulled = widest->reference;
            children.erase(widest);
            appendChildren(bvh2_.nodes.at(pulled), children);
        }

        gpu::Bvh4Node node{};
        node.children = gpu::uvec4(gpu::BVH4_EMPTY_CHILD);
        for (size_t i = 0; i < children.size; ++i) {
            const Child& c = children.items[i];
            const auto slot = static_cast<int>(i);
            node.minX[slot] = c.box.lo.x, node.maxX[slot] = c.box.hi.x;
            node.minY[slot] = c.box.lo.y, node.maxY[slot] = c.box.hi.y;
            node.minZ[slot] = c.box.lo.z, node.maxZ[slot] = c.box.hi.z;
            if (c.inner()) {
                node.children[slot] = emit(c.reference, depth + 1);
            } else {
                node.children[slot] = leafWord(c);
                out_.depth = std::max(out_.depth, depth + 1);
                ++out_.leafCount;
            }
        }
        out_.childSlotsUsed += static_cast<uint32_t>(children.size);
        out_.nodes[index] = node;  // after the recursion: emplace_back may have moved the vector
        return index;
    }

private:
    const Bvh& bvh2_;
    size_t maxChildren_;
    Bvh4& out_;
};

}  // namespace

Bvh4 collapseToBvh4(const Bvh& bvh2, uint32_t maxChildren) {
    if (maxChildren < 2 || maxChildren > 4)
        throw std::invalid_argument("collapseToBvh4: maxChildren must be 2, 3 or 4, not " +
                                    std::to_string(maxChildren));
    Bvh4 out;
    if (bvh2.nodes.empty()) return out;
    out.nodes.reserve(bvh2.nodes.size() / 2 + 1);
    Collapser(bvh2, maxChildren, out).emit(0, 1);
    return out;
}

}  // namespace ripple::bvh
