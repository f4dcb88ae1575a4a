// Splitting a NanoVDB grid over ranks (see NanoVdbPartition.h).
#include "apps/scene/NanoVdbPartition.h"

#include "apps/scene/KdSplit.h"

#include "core/scene/NanoVdbTree.h"

#include <nanovdb/util/GridBuilder.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace ripple::apps {

namespace {

using Leaf = nanovdb::NanoLeaf<float>;

struct LeafCount {
    glm::ivec3 centre;  // of its 8^3 voxels (origin + 4)
    uint64_t active;
};

}  // namespace

NanoVdbFile nanoVdbPart(const NanoVdbFile& whole, uint32_t rank, uint32_t ranks) {
    if (ranks <= 1) return whole;
    std::optional<core::CheckedNanoVdbGrid> checked;
    try {
        checked.emplace(whole.grid);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string("the grid cannot be split: ") + e.what());
    }
    const nanovdb::NanoGrid<float>& grid = checked->grid();
    const auto& root = grid.tree().root();
    const nanovdb::CoordBBox box = root.bbox();
    if (box.empty()) throw std::runtime_error("the grid has no active voxel to split over ranks");
    const float background = root.background();

    struct Tile {
        nanovdb::Coord lo, hi;
        float value;
    };
    std::vector<Tile> tiles;
    std::vector<const Leaf*> leafNodes;
    std::vector<LeafCount> counts;
    try {
        checked->walk(
            [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float value) {
                if (value != background) tiles.push_back({lo, hi, value});
            },
            [&](const Leaf& leaf) {
                leafNodes.push_back(&leaf);
                const nanovdb::Coord o = leaf.origin();
                counts.push_back({glm::ivec3(o[0], o[1], o[2]) + 4, leaf.valueMask().countOn()});
            });
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string("the grid cannot be split: ") + e.what());
    }
    // Voxel boxes [lo, hi], inclusive: the two sides of a cut share its plane of voxels.
    const KdBox wholeBox{glm::i64vec3(box.min()[0], box.min()[1], box.min()[2]), glm::i64vec3(box.max()[0], box.max()[1], box.max()[2])};
    const KdBox region = kdRegion(wholeBox, rank, ranks, [&](const KdBox& r) {
        uint64_t n = 0;
        for (const LeafCount& l : counts)
            if (glm::all(glm::greaterThanEqual(glm::i64vec3(l.centre), r.lo)) && glm::all(glm::lessThanEqual(glm::i64vec3(l.centre), r.hi)))
                n += l.active;
        return double(n);
    });
    const nanovdb::Coord lo(int(region.lo.x), int(region.lo.y), int(region.lo.z)), hi(int(region.hi.x), int(region.hi.y), int(region.hi.z));
    const auto inRegion = [&](const nanovdb::Coord& c) {
        return c[0] >= lo[0] && c[1] >= lo[1] && c[2] >= lo[2] && c[0] <= hi[0] && c[1] <= hi[1] && c[2] <= hi[2];
    };

    nanovdb::GridBuilder<float> builder(background);
    auto voxels = builder.getAccessor();
    // Voxels that are active or hold a value other than the background (the kernels read inactive values too).
    for (const Leaf* leaf : leafNodes)
        for (uint32_t v = 0; v < Leaf::SIZE; ++v) {
            const nanovdb::Coord c = leaf->origin() + Leaf::OffsetToLocalCoord(v);
            if (inRegion(c) && (leaf->isActive(c) || leaf->getValue(v) != background)) voxels.setValue(c, leaf->getValue(v));
        }
    uint64_t tileVoxels = 0;
    for (const Tile& t : tiles) {
        nanovdb::Coord from, to;
        for (int a = 0; a < 3; ++a) {
            from[a] = std::max(t.lo[a], lo[a]);
            to[a] = std::min(t.hi[a], hi[a]);
        }
        if (from[0] > to[0] || from[1] > to[1] || from[2] > to[2]) continue;
        tileVoxels += uint64_t(to[0] - from[0] + 1) * uint64_t(to[1] - from[1] + 1) * uint64_t(to[2] - from[2] + 1);
        if (tileVoxels > (uint64_t(1) << 28))
            throw std::runtime_error("its tiles would fill more than 2^28 voxels of rank " + std::to_string(rank) + "'s region");
        for (int z = from[2]; z <= to[2]; ++z)
            for (int y = from[1]; y <= to[1]; ++y)
                for (int x = from[0]; x <= to[0]; ++x) voxels.setValue(nanovdb::Coord(x, y, z), t.value);
    }
    // The region's corners, so that the part's active box (its field's extent) is the region.
    const auto wholeValues = grid.getAccessor();
    voxels.setValue(lo, wholeValues.getValue(lo));
    voxels.setValue(hi, wholeValues.getValue(hi));

    NanoVdbFile part = whole;
    const auto handle = builder.getHandle(grid.map(), whole.name);
    part.grid.assign(handle.data(), handle.data() + handle.size());
    return part;
}

}  // namespace ripple::apps
