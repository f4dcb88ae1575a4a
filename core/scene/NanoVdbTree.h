// A NanoVDB float grid buffer, checked before anything reads it, and a walk over its tree: the one check of
// NanoVDB grids Ripple has. The device's field (NanoVdbGrid.h) and the tools' split of a grid over ranks
// (apps/scene/NanoVdbPartition.h) both read grids through it. Header-only NanoVDB, no Vulkan: its own small
// library (ripple_nanovdb), which ripple_core and the tools link.
#pragma once

#include <nanovdb/NanoVDB.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace ripple::core {

// NanoVDB's name of a grid type ("float", "double", ...), or "unknown type N" past the types it knows.
std::string gridTypeName(uint32_t type);

class CheckedNanoVdbGrid {
public:
    // Copies `blob` to memory aligned as NanoVDB's structures need and checks its header: at least a grid's
    // header long, the magic number, the major version (32), a float grid, a stated size within the blob and
    // within 32-bit addressing, the root node and its tile table inside the grid, a finite background, an
    // invertible map. Throws std::invalid_argument naming the first problem.
    explicit CheckedNanoVdbGrid(std::span<const uint8_t> blob);

    const nanovdb::NanoGrid<float>& grid() const { return *reinterpret_cast<const nanovdb::NanoGrid<float>*>(aligned_.data()); }
    std::span<const uint8_t> bytes() const { return {reinterpret_cast<const uint8_t*>(aligned_.data()), size_t(bytes_)}; }

    // Every tile (of the root, an upper or a lower node: its index box, inclusive, and value) and every leaf,
    // in tree order. Each child is checked to lie whole inside the grid, aligned, before it is read, and every
    // value to be finite; throws std::invalid_argument naming the first problem.
    void walk(const std::function<void(const nanovdb::Coord& lo, const nanovdb::Coord& hi, float value)>& tile,
              const std::function<void(const nanovdb::NanoLeaf<float>& leaf)>& leaf) const;

private:
    struct alignas(NANOVDB_DATA_ALIGNMENT) Block {
        uint8_t bytes[NANOVDB_DATA_ALIGNMENT];
    };
    std::vector<Block> aligned_;
    uint64_t bytes_ = 0;
};

}  // namespace ripple::core
