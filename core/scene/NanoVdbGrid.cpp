// Checking a NanoVDB grid buffer and its macrocell value ranges (see NanoVdbGrid.h).
#include "core/scene/NanoVdbGrid.h"

#include "shaders/shared/volume.h"

#include <nanovdb/NanoVDB.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

using Grid = nanovdb::NanoGrid<float>;
using Root = nanovdb::NanoRoot<float>;
using Upper = nanovdb::NanoUpper<float>;
using Lower = nanovdb::NanoLower<float>;
using Leaf = nanovdb::NanoLeaf<float>;

// The blob copied to memory aligned as NanoVDB's structures are (32 bytes).
struct alignas(NANOVDB_DATA_ALIGNMENT) Block {
    uint8_t bytes[NANOVDB_DATA_ALIGNMENT];
};

// Whether `size` bytes at `p` lie inside [begin, begin + bytes) on NanoVDB's alignment.
bool inside(const void* p, size_t size, const uint8_t* begin, uint64_t bytes) {
    const auto* q = static_cast<const uint8_t*>(p);
    if (q < begin) return false;
    const uint64_t offset = uint64_t(q - begin);
    return offset % NANOVDB_DATA_ALIGNMENT == 0 && offset <= bytes && size <= bytes - offset;
}

void widen(glm::vec2& range, float value) { range = glm::vec2(std::min(range.x, value), std::max(range.y, value)); }

}  // namespace

std::shared_ptr<const NanoVdbGrid> prepareNanoVdbGrid(std::span<const uint8_t> blob) {
    if (blob.size() < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>))
        throw std::invalid_argument(std::to_string(blob.size()) + " bytes, too short for a NanoVDB grid");
    if (blob.size() > size_t(UINT32_MAX) - 64)
        throw std::invalid_argument("a buffer of " + std::to_string(blob.size()) + " bytes, larger than the kernels' 32-bit addressing");
    const size_t size = blob.size();
    std::vector<Block> copy((size + sizeof(Block) - 1) / sizeof(Block));
    std::copy(blob.begin(), blob.begin() + std::ptrdiff_t(size), reinterpret_cast<uint8_t*>(copy.data()));
    const auto* begin = reinterpret_cast<const uint8_t*>(copy.data());
    const auto* data = reinterpret_cast<const nanovdb::GridData*>(begin);
    if (data->mMagic != NANOVDB_MAGIC_NUMBER) throw std::invalid_argument("not a NanoVDB grid (its magic number is wrong)");
    if (data->mVersion.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
        throw std::invalid_argument("NanoVDB version " + std::to_string(data->mVersion.getMajor()) + "." +
                                    std::to_string(data->mVersion.getMinor()) + "; Ripple reads major version " +
                                    std::to_string(NANOVDB_MAJOR_VERSION_NUMBER));
    if (data->mGridType != nanovdb::GridType::Float)
        throw std::invalid_argument(std::string("a grid of ") + nanovdb::toStr(data->mGridType) + "; Ripple reads float grids");
    const uint64_t bytes = data->mGridSize;
    if (bytes > blob.size() || bytes < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>))
        throw std::invalid_argument("the grid says it is " + std::to_string(bytes) + " bytes in a buffer of " +
                                    std::to_string(blob.size()));
    if (bytes > uint64_t(UINT32_MAX) - 64)
        throw std::invalid_argument("the grid is larger than the kernels' 32-bit addressing");
    const Grid* grid = reinterpret_cast<const Grid*>(begin);
    const auto& treeData = *reinterpret_cast<const nanovdb::TreeData<3>*>(begin + sizeof(nanovdb::GridData));
    const auto* rootBytes = begin + sizeof(nanovdb::GridData) + treeData.mNodeOffset[3];
    if (treeData.mNodeOffset[3] > bytes || !inside(rootBytes, sizeof(Root), begin, bytes))
        throw std::invalid_argument("the grid's root node lies outside it");
    const Root& root = *reinterpret_cast<const Root*>(rootBytes);
    const uint32_t tiles = root.tileCount();
    if (!inside(rootBytes, sizeof(Root) + uint64_t(tiles) * sizeof(typename Root::Tile), begin, bytes))
        throw std::invalid_argument("the root's " + std::to_string(tiles) + " tiles run past the grid");

    auto out = std::make_shared<NanoVdbGrid>();
    const nanovdb::CoordBBox box = root.bbox();
    const float background = root.background();
    if (!std::isfinite(background)) throw std::invalid_argument("the background value is not finite");
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
    const auto coverTile = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
        cover(lo, hi, v);
        markCovered(lo, hi);
    };
    for (uint32_t t = 0; t < tiles; ++t) {
        const auto* tile = root.data()->tile(t);
        const nanovdb::Coord origin = tile->origin();
        if (!tile->isChild()) {
            coverTile(origin, origin + nanovdb::Coord(Upper::DIM - 1), tile->value);
            continue;
        }
        const Upper* upper = root.data()->getChild(tile);
        if (!inside(upper, sizeof(Upper), begin, bytes)) throw std::invalid_argument("root tile " + std::to_string(t) + "'s child lies outside the grid");
        for (uint32_t n = 0; n < Upper::SIZE; ++n) {
            const nanovdb::Coord at = upper->offsetToGlobalCoord(n);
            if (!upper->data()->isChild(n)) {
                coverTile(at, at + nanovdb::Coord(Lower::DIM - 1), upper->data()->getValue(n));
                continue;
            }
            const Lower* lower = upper->data()->getChild(n);
            if (!inside(lower, sizeof(Lower), begin, bytes)) throw std::invalid_argument("an upper node's child lies outside the grid");
            for (uint32_t k = 0; k < Lower::SIZE; ++k) {
                const nanovdb::Coord leafAt = lower->offsetToGlobalCoord(k);
                if (!lower->data()->isChild(k)) {
                    coverTile(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1), lower->data()->getValue(k));
                    continue;
                }
                const Leaf* leaf = lower->data()->getChild(k);
                if (!inside(leaf, sizeof(Leaf), begin, bytes)) throw std::invalid_argument("a lower node's child lies outside the grid");
                for (uint32_t v = 0; v < Leaf::SIZE; ++v) {
                    const float value = leaf->getValue(v);
                    if (!std::isfinite(value)) throw std::invalid_argument("a voxel value is not finite");
                    const nanovdb::Coord voxel = leafAt + Leaf::OffsetToLocalCoord(v);
                    cover(voxel, voxel, value);
                }
                markCovered(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1));
                ++out->leaves;
            }
        }
    }
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
    const double determinant = glm::determinant(glm::dmat3(out->indexToObject));
    if (!std::isfinite(determinant) || determinant == 0.0) throw std::invalid_argument("the grid's map is not invertible");

    out->words.assign(8, 0u);
    std::memcpy(out->words.data(), &out->base, sizeof(out->base));
    out->words.resize(8 + (bytes + 3) / 4);
    std::memcpy(out->words.data() + 8, begin, bytes);
    return out;
}

}  // namespace ripple::core
