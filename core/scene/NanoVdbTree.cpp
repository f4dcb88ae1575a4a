// The checked NanoVDB grid and its tree walk (see NanoVdbTree.h).
#include "core/scene/NanoVdbTree.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

using Root = nanovdb::NanoRoot<float>;
using Upper = nanovdb::NanoUpper<float>;
using Lower = nanovdb::NanoLower<float>;
using Leaf = nanovdb::NanoLeaf<float>;

// Whether `size` bytes at `p` lie inside [begin, begin + bytes) on NanoVDB's alignment.
bool inside(const void* p, size_t size, const uint8_t* begin, uint64_t bytes) {
    const auto* q = static_cast<const uint8_t*>(p);
    if (q < begin) return false;
    const uint64_t offset = uint64_t(q - begin);
    return offset % NANOVDB_DATA_ALIGNMENT == 0 && offset <= bytes && size <= bytes - offset;
}

}  // namespace

std::string gridTypeName(uint32_t type) {
    // nanovdb::toStr indexes its table with the type unchecked.
    return type < uint32_t(nanovdb::GridType::End) ? nanovdb::toStr(nanovdb::GridType(type)) : "unknown type " + std::to_string(type);
}

CheckedNanoVdbGrid::CheckedNanoVdbGrid(std::span<const uint8_t> blob) {
    if (blob.size() < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>))
        throw std::invalid_argument(std::to_string(blob.size()) + " bytes, too short for a NanoVDB grid");
    if (blob.size() > size_t(UINT32_MAX) - 64)
        throw std::invalid_argument("a buffer of " + std::to_string(blob.size()) + " bytes, larger than the kernels' 32-bit addressing");
    aligned_.resize((blob.size() + sizeof(Block) - 1) / sizeof(Block));
    std::copy(blob.begin(), blob.end(), reinterpret_cast<uint8_t*>(aligned_.data()));
    const auto* begin = reinterpret_cast<const uint8_t*>(aligned_.data());
    const auto* data = reinterpret_cast<const nanovdb::GridData*>(begin);
    if (data->mMagic != NANOVDB_MAGIC_NUMBER) throw std::invalid_argument("not a NanoVDB grid (its magic number is wrong)");
    if (data->mVersion.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
        throw std::invalid_argument("NanoVDB version " + std::to_string(data->mVersion.getMajor()) + "." +
                                    std::to_string(data->mVersion.getMinor()) + "; Ripple reads major version " +
                                    std::to_string(NANOVDB_MAJOR_VERSION_NUMBER));
    if (data->mGridType != nanovdb::GridType::Float)
        throw std::invalid_argument("a grid of " + gridTypeName(uint32_t(data->mGridType)) + "; Ripple reads float grids");
    bytes_ = data->mGridSize;
    if (bytes_ > blob.size() || bytes_ < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>))
        throw std::invalid_argument("the grid says it is " + std::to_string(bytes_) + " bytes in a buffer of " +
                                    std::to_string(blob.size()));
    const auto& treeData = *reinterpret_cast<const nanovdb::TreeData<3>*>(begin + sizeof(nanovdb::GridData));
    const auto* rootBytes = begin + sizeof(nanovdb::GridData) + treeData.mNodeOffset[3];
    if (treeData.mNodeOffset[3] > bytes_ || !inside(rootBytes, sizeof(Root), begin, bytes_))
        throw std::invalid_argument("the grid's root node lies outside it");
    const Root& root = *reinterpret_cast<const Root*>(rootBytes);
    const uint32_t tiles = root.tileCount();
    if (!inside(rootBytes, sizeof(Root) + uint64_t(tiles) * sizeof(typename Root::Tile), begin, bytes_))
        throw std::invalid_argument("the root's " + std::to_string(tiles) + " tiles run past the grid");
    if (!std::isfinite(root.background())) throw std::invalid_argument("the background value is not finite");
    const nanovdb::Map& map = grid().map();
    const glm::dmat3 m(map.mMatD[0], map.mMatD[3], map.mMatD[6], map.mMatD[1], map.mMatD[4], map.mMatD[7], map.mMatD[2],
                       map.mMatD[5], map.mMatD[8]);
    const double determinant = glm::determinant(m);
    if (!std::isfinite(determinant + map.mVecD[0] + map.mVecD[1] + map.mVecD[2]) || determinant == 0.0)
        throw std::invalid_argument("the grid's map is not invertible");
}

void CheckedNanoVdbGrid::walk(const std::function<void(const nanovdb::Coord&, const nanovdb::Coord&, float)>& tile,
                              const std::function<void(const nanovdb::NanoLeaf<float>&)>& leaf) const {
    const auto* begin = reinterpret_cast<const uint8_t*>(aligned_.data());
    const Root& root = grid().tree().root();
    const auto tileValue = [&](const nanovdb::Coord& lo, const nanovdb::Coord& hi, float v) {
        if (!std::isfinite(v)) throw std::invalid_argument("a tile or voxel value is not finite");
        tile(lo, hi, v);
    };
    for (uint32_t t = 0; t < root.tileCount(); ++t) {
        const auto* rootTile = root.data()->tile(t);
        const nanovdb::Coord origin = rootTile->origin();
        if (!rootTile->isChild()) {
            tileValue(origin, origin + nanovdb::Coord(Upper::DIM - 1), rootTile->value);
            continue;
        }
        const Upper* upper = root.data()->getChild(rootTile);
        if (!inside(upper, sizeof(Upper), begin, bytes_)) throw std::invalid_argument("root tile " + std::to_string(t) + "'s child lies outside the grid");
        for (uint32_t n = 0; n < Upper::SIZE; ++n) {
            const nanovdb::Coord at = upper->offsetToGlobalCoord(n);
            if (!upper->data()->isChild(n)) {
                tileValue(at, at + nanovdb::Coord(Lower::DIM - 1), upper->data()->getValue(n));
                continue;
            }
            const Lower* lower = upper->data()->getChild(n);
            if (!inside(lower, sizeof(Lower), begin, bytes_)) throw std::invalid_argument("an upper node's child lies outside the grid");
            for (uint32_t k = 0; k < Lower::SIZE; ++k) {
                const nanovdb::Coord leafAt = lower->offsetToGlobalCoord(k);
                if (!lower->data()->isChild(k)) {
                    tileValue(leafAt, leafAt + nanovdb::Coord(Leaf::DIM - 1), lower->data()->getValue(k));
                    continue;
                }
                const Leaf* l = lower->data()->getChild(k);
                if (!inside(l, sizeof(Leaf), begin, bytes_)) throw std::invalid_argument("a lower node's child lies outside the grid");
                for (uint32_t v = 0; v < Leaf::SIZE; ++v)
                    if (!std::isfinite(l->getValue(v))) throw std::invalid_argument("a voxel value is not finite");
                leaf(*l);
            }
        }
    }
}

}  // namespace ripple::core
