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
    if (box.empty()) {
        out->base = glm::ivec3(0);
        out->macrocells = glm::uvec3(1u);
    } else {
        for (int a = 0; a < 3; ++a) out->base[a] = box.min()[a] & ~7;
        // Up to one voxel past the box: linear filtering reads it.
        for (int a = 0; a < 3; ++a)
            out->macrocells[a] = uint32_t((int64_t(box.max()[a]) + 2 - out->base[a] + 7) / 8);
    }
    if (uint64_t(out->macrocells.x) * out->macrocells.y * out->macrocells.z > (uint64_t(1) << 27))
        throw std::invalid_argument("the grid's active box is too large for its macrocell grid");
    const glm::uvec3 m = out->macrocells;
    // Every macrocell lies whole in one leaf, one tile (of a lower node, an upper node or the root) or none
    // of them (the background): their regions are aligned to multiples of 8.
    std::vector<glm::vec2> ranges(size_t(m.x) * m.y * m.z, glm::vec2(INFINITY, -INFINITY));
    // The value `v` over index box [lo, hi] (inclusive), where it meets the macrocell grid.
    const auto cover = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
        if (!std::isfinite(v)) throw std::invalid_argument("a tile or voxel value is not finite");
        glm::ivec3 first, last;
        for (int a = 0; a < 3; ++a) {
            const int64_t from = (int64_t(lo[a]) - out->base[a]) >> 3, to = (int64_t(hi[a]) - out->base[a]) >> 3;
            if (to < 0 || from >= int64_t(m[a])) return;  // outside the grid's box
            first[a] = int(std::max<int64_t>(from, 0));
            last[a] = int(std::min<int64_t>(to, int64_t(m[a]) - 1));
        }
        widen(out->valueRange, v);
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) widen(ranges[(size_t(z) * m.y + y) * m.x + x], v);
    };
    for (uint32_t t = 0; t < tiles; ++t) {
        const auto* tile = root.data()->tile(t);
        const nanovdb::Coord origin = tile->origin();
        if (!tile->isChild()) {
            cover(origin, origin + nanovdb::Coord(Upper::DIM - 1), tile->value);
            continue;
        }
        const Upper* upper = root.data()->getChild(tile);
        if (!inside(upper, sizeof(Upper), begin, bytes)) throw std::invalid_argument("root tile " + std::to_string(t) + "'s child lies outside the grid");
        for (uint32_t n = 0; n < Upper::SIZE; ++n) {
            const nanovdb::Coord at = upper->offsetToGlobalCoord(n);
            if (!upper->data()->isChild(n)) {
                cover(at, at + nanovdb::Coord(Lower::DIM - 1), upper->data()->getValue(n));
                continue;
            }
            const Lower* lower = upper->data()->getChild(n);
            if (!inside(lower, sizeof(Lower), begin, bytes)) throw std::invalid_argument("an upper node's child lies outside the grid");
            for (uint32_t k = 0; k < Lower::SIZE; ++k) {
                const nanovdb::Coord leafAt = lower->offsetToGlobalCoord(k);
                if (!lower->data()->isChild(k)) {
                    cover(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1), lower->data()->getValue(k));
                    continue;
                }
                const Leaf* leaf = lower->data()->getChild(k);
                if (!inside(leaf, sizeof(Leaf), begin, bytes)) throw std::invalid_argument("a lower node's child lies outside the grid");
                float lowest = INFINITY, highest = -INFINITY;
                for (uint32_t v = 0; v < Leaf::SIZE; ++v) {
                    const float value = leaf->getValue(v);
                    if (!std::isfinite(value)) throw std::invalid_argument("a voxel value is not finite");
                    lowest = std::min(lowest, value);
                    highest = std::max(highest, value);
                }
                cover(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1), lowest);
                cover(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1), highest);
                ++out->leaves;
            }
        }
    }
    for (glm::vec2& range : ranges)
        if (range.y < range.x) {
            range = glm::vec2(background);
            widen(out->valueRange, background);
        }
    // Linear filtering at a point of macrocell (x, y, z) also reads the voxels one further along each axis.
    out->macrocellRanges.resize(ranges.size());
    for (uint32_t z = 0; z < m.z; ++z)
        for (uint32_t y = 0; y < m.y; ++y)
            for (uint32_t x = 0; x < m.x; ++x) {
                glm::vec2 r(INFINITY, -INFINITY);
                for (uint32_t d = 0; d < 8; ++d) {
                    const glm::uvec3 n = glm::min(glm::uvec3(x + (d & 1), y + ((d >> 1) & 1), z + (d >> 2)), m - 1u);
                    const glm::vec2 o = ranges[(size_t(n.z) * m.y + n.y) * m.x + n.x];
                    r = glm::vec2(std::min(r.x, o.x), std::max(r.y, o.y));
                }
                out->macrocellRanges[(size_t(z) * m.y + y) * m.x + x] = r;
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
