// NanoVDB grids (ANARI's KHR_SPATIAL_FIELD_NANOVDB: a NanoVDB grid buffer) made ready for the kernels: the
// buffer is checked on the host before any kernel reads it (header, version, grid type, and every node the
// tree reaches lying whole inside the buffer), then copied behind a small header for the kernels, which read
// it through NanoVDB's own portable header (PNanoVDB.h, shaders/nanovdb.glsl). The field spans the grid's
// active box, as a structuredRegular field spans its samples; a grid of macrocells over it holds the range of
// values each can take, from the tree's own leaves and tiles, for the majorants of delta and ratio tracking.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace ripple::core {

struct NanoVdbGrid {
    // The device buffer: 8 words (the index of grid space's origin, x y z, then padding), then the grid.
    std::vector<uint32_t> words;
    glm::ivec3 base{0};                  // index coordinate of grid space's origin: the active box's lowest voxel
    glm::uvec3 extent{8u};               // the field spans grid space [0, extent]: the active box (at least 1 a side)
    glm::uvec3 macrocells{1u};           // per axis: extent / 8, rounded up
    // Per macrocell (x fastest): a range holding every value the interpolated field takes there (from its
    // voxels and those one further along each axis, which linear filtering reads).
    std::vector<glm::vec2> macrocellRanges;
    glm::dmat4 indexToObject{1.0};       // the grid's map: index space to the field's object space
    glm::vec2 valueRange{0.0f};          // of the voxels and tiles in the grid's box (and the background where none is)
    uint64_t leaves = 0;
};

// Checks `blob` and prepares it. Throws std::invalid_argument naming the first problem: too short, not a
// NanoVDB grid (magic), another major version, not a float grid, a size past the blob, a node or tile
// table outside the blob or misaligned, a value that is not finite.
std::shared_ptr<const NanoVdbGrid> prepareNanoVdbGrid(std::span<const uint8_t> blob);

}  // namespace ripple::core
