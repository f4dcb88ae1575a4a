// Block-structured AMR hierarchies (ANARI spatial field "amr", as anari-ospray defines it) made ready for the
// kernels: checked, then packed into the 32-bit words shaders/shared/volume.h's AmrHeader describes. A grid
// of macrocells over the hierarchy's box lists, per macrocell, the blocks that overlap it, finest level first,
// and holds the range of the values of their cells there, from which VolumeTable takes the majorants of delta
// and ratio tracking through any transfer function.
//
// Reconstruction: the value at a point is the value of the finest cell that covers it (piecewise constant;
// shaders/amr.glsl). Where a finer level covers a coarser one, the coarser cells there are never read.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ripple::core {

// One block: the cells lower..upper (inclusive) of its level's index space, with a value each (x fastest).
struct AmrBlock {
    uint32_t level = 0;
    glm::ivec3 lower{0}, upper{0};
    std::vector<float> values;
};

// A hierarchy as ANARI's "amr" field gives it: cell (i, j, k) of level l spans
// origin + spacing * cellWidth[l] * ([i, i + 1], [j, j + 1], [k, k + 1]) in object space.
struct AmrHierarchy {
    std::vector<float> cellWidth;        // per level, decreasing
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};
    std::vector<AmrBlock> blocks;
};

struct AmrGrid {
    std::vector<uint32_t> words;         // the device buffer (AmrHeader first)
    glm::vec3 lo{0.0f}, hi{0.0f};        // object-space box of the blocks
    glm::uvec3 macrocells{1u};           // per axis; grid space spans [0, 8 * macrocells] from lo
    glm::dmat4 objectToGrid{1.0};        // the field's object space to grid space
    // Per macrocell (x fastest), the lowest and highest value of the cells of the blocks overlapping it (hi < lo:
    // no block does; the macrocell is empty).
    std::vector<glm::vec2> macrocellRanges;
    glm::vec2 valueRange{0.0f};          // of every cell
    uint32_t levels = 0;                 // levels that hold a block
    uint64_t cells = 0;
};

// The most cells a hierarchy may hold (the kernels index values with 32-bit offsets).
constexpr uint64_t kMaxAmrCells = uint64_t(1) << 30;

// Checks and packs `hierarchy`. Throws std::invalid_argument naming the first problem: no block or level, a
// cell width that is not finite and positive or does not decrease from level to level, a block of a level
// with no cell width, an empty or inverted box, a block whose values do not match its cells, a value that is
// not finite, two blocks of one level that overlap, a block outside the box of the coarsest level's blocks,
// index coordinates past +-2^24, or more than kMaxAmrCells cells.
std::shared_ptr<const AmrGrid> prepareAmrGrid(const AmrHierarchy& hierarchy);

}  // namespace ripple::core
