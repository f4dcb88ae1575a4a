// A NanoVDB grid buffer made ready for the kernels, and its macrocell value ranges (see NanoVdbGrid.h).
#include "core/scene/NanoVdbGrid.h"

#include "core/scene/NanoVdbTree.h"
#include "shaders/shared/volume.h"

#include <nanovdb/NanoVDB.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

using Leaf = nanovdb::NanoLeaf<float>;

void widen(glm::vec2& range, float value) { range = glm::vec2(std::min(range.x, value), std::max(range.y, value)); }

}  // namespace

std::shared_ptr<const NanoVdbGrid> prepareNanoVdbGrid(std::span<const uint8_t> blob) {
    const CheckedNanoVdbGrid checked(blob);
    const nanovdb::NanoGrid<float>* grid = &checked.grid();
    const nanovdb::NanoRoot<float>& root = grid->tree().root();
    auto out = std::make_shared<NanoVdbGrid>();
    const nanovdb::CoordBBox box = root.bbox();
    const float background = root.background();  // finite: checked
    out->valueRange = glm::vec2(INFINITY, -INFINITY);
    // The field spans the active box, from its lowest voxel to its highest, as a structuredRegular field spans
    // its samples (at least one voxel's width along each axis). Macrocell m (per axis) reads voxels base + 8m
    // to base + 8m + 8, the last through linear filtering's neighbour; its range holds every value among them:
    // each leaf's voxels one by one, each tile's value over its box, and the background over each 8^3 block
    // (aligned as NanoVDB's nodes are: each lies whole in one leaf, one tile or none) that no node covers.
    glm::ivec3 alignedBase(0);
    glm::uvec3 aligned(1u);
    if (box.empty()) {
        out->base = glm::ivec3(0);
        out->extent = glm::uvec3(8u);
    } else {
        for (int a = 0; a < 3; ++a) {
            out->base[a] = box.min()[a];
            out->extent[a] = uint32_t(std::max<int64_t>(int64_t(box.max()[a]) - box.min()[a], 1));
            alignedBase[a] = box.min()[a] & ~7;
            aligned[a] = uint32_t((int64_t(box.max()[a]) + 1 - alignedBase[a]) / 8 + 1);
        }
    }
    out->macrocells = glm::max((out->extent + 7u) / 8u, glm::uvec3(1u));
    if (uint64_t(aligned.x) * aligned.y * aligned.z > (uint64_t(1) << 27) ||
        uint64_t(out->macrocells.x) * out->macrocells.y * out->macrocells.z > (uint64_t(1) << 27))
        throw std::invalid_argument("the grid's active box is too large for its macrocell grid");
    const glm::uvec3 mc = out->macrocells;
    out->macrocellRanges.assign(size_t(mc.x) * mc.y * mc.z, glm::vec2(INFINITY, -INFINITY));
    // The value `v` over index box [lo, hi] (inclusive), in every macrocell that reads a voxel of it.
    const auto cover = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
        if (!std::isfinite(v)) throw std::invalid_argument("a tile or voxel value is not finite");
        glm::ivec3 first, last;
        for (int a = 0; a < 3; ++a) {
            const int64_t from = (int64_t(lo[a]) - out->base[a] - 1) >> 3, to = (int64_t(hi[a]) - out->base[a]) >> 3;
            if (to < 0 || from >= int64_t(mc[a])) return;  // outside the field's box
            first[a] = int(std::max<int64_t>(from, 0));
            last[a] = int(std::min<int64_t>(to, int64_t(mc[a]) - 1));
        }
        widen(out->valueRange, v);
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) widen(out->macrocellRanges[(size_t(z) * mc.y + y) * mc.x + x], v);
    };
    // The aligned blocks some node covers (the rest read the background).
    const glm::uvec3 m = aligned;
    std::vector<uint8_t> covered(size_t(m.x) * m.y * m.z, 0);
    const auto markCovered = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi) {
        glm::ivec3 first, last;
        for (int a = 0; a < 3; ++a) {
            const int64_t from = (int64_t(lo[a]) - alignedBase[a]) >> 3, to = (int64_t(hi[a]) - alignedBase[a]) >> 3;
            if (to < 0 || from >= int64_t(m[a])) return;
            first[a] = int(std::max<int64_t>(from, 0));
            last[a] = int(std::min<int64_t>(to, int64_t(m[a]) - 1));
        }
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) covered[(size_t(z) * m.y + y) * m.x + x] = 1;
    };
    checked.walk(
        [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
            cover(lo, hi, v);
            markCovered(lo, hi);
        },
        [&](const Leaf& leaf) {
            for (uint32_t v = 0; v < Leaf::SIZE; ++v) {
                const nanovdb::Coord voxel = leaf.origin() + Leaf::OffsetToLocalCoord(v);
                cover(voxel, voxel, leaf.getValue(v));
            }
            markCovered(leaf.origin(), leaf.origin() + nanovdb::Coord(Leaf::DIM - 1));
            ++out->leaves;
        });
    for (uint32_t z = 0; z < m.z; ++z)
        for (uint32_t y = 0; y < m.y; ++y)
            for (uint32_t x = 0; x < m.x; ++x)
                if (!covered[(size_t(z) * m.y + y) * m.x + x]) {
                    const nanovdb::Coord lo(alignedBase.x + 8 * int(x), alignedBase.y + 8 * int(y), alignedBase.z + 8 * int(z));
                    cover(lo, lo + nanovdb::Coord(7), background);
                }

    // The grid's map (index to world, which is the field's object space): world = M index + v, M row-major.
    const nanovdb::Map& map = grid->map();
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) out->indexToObject[column][row] = map.mMatD[row * 3 + column];
    out->indexToObject[3] = glm::dvec4(map.mVecD[0], map.mVecD[1], map.mVecD[2], 1.0);

    out->words.assign(8, 0u);
    std::memcpy(out->words.data(), &out->base, sizeof(out->base));
    const std::span<const uint8_t> bytes = checked.bytes();
    out->words.resize(8 + (bytes.size() + 3) / 4);
    std::memcpy(out->words.data() + 8, bytes.data(), bytes.size());
    return out;
}

}  // namespace ripple::core
