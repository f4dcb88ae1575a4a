// Unstructured meshes (ANARI's KHR_SPATIAL_FIELD_UNSTRUCTURED: tetrahedra, hexahedra, wedges and
// pyramids with values per vertex or per cell) made ready for the kernels: checked, packed into the 32-bit
// words shaders/shared/volume.h's UnstructuredHeader describes, with a BVH over the cells for point location
// (shaders/unstructured.glsl) and a grid of macrocells over the mesh's box holding the range of values of the
// cells that overlap each one, from which VolumeTable takes the majorants of delta and ratio tracking
// through any transfer function.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ripple::core {

// ANARI's layout: cell c's corners are index[cellIndex[c] ..] in VTK's vertex order for cellType[c].
struct UnstructuredCells {
    std::vector<glm::vec3> positions;
    std::vector<float> values;           // one per vertex, or one per cell when cellCentered
    bool cellCentered = false;
    std::vector<uint32_t> index;
    std::vector<uint32_t> cellIndex;
    std::vector<uint8_t> cellType;       // VTK's codes: 10 tetrahedron, 12 hexahedron, 13 wedge, 14 pyramid
};

// Corners of a cell of VTK type `type`; 0 for a type Ripple does not take.
uint32_t unstructuredCorners(uint8_t type);

struct UnstructuredGrid {
    std::vector<uint32_t> words;         // the device buffer (UnstructuredHeader first)
    glm::vec3 lo{0.0f}, hi{0.0f};        // object-space box of the kept cells
    glm::uvec3 macrocells{1u};           // per axis; the grid space spans [0, 8 * macrocells] over [lo, hi]
    // Per macrocell (x fastest), the lowest and highest value the field takes in the cells overlapping it
    // (hi < lo: none does, the macrocell is empty).
    std::vector<glm::vec2> macrocellRanges;
    glm::vec3 gridScale{1.0f};           // grid space is (object - lo) * gridScale
    bool cellCentered = false;           // values per cell (constant over each), else per vertex
    // Per kept cell in leaf order (the words' order): its object-space box and the range of its values
    // (iso-surfaces are built over the cells whose range holds an isovalue).
    std::vector<std::pair<glm::vec3, glm::vec3>> cellBoxes;
    std::vector<glm::vec2> cellRanges;
    uint64_t cellsKept = 0;
    uint64_t degenerateCells = 0;        // zero volume: dropped
    uint64_t invertedCells = 0;          // corners in the order opposite to VTK's: kept (the inverse map needs no orientation)
    uint32_t bvhDepth = 0;
    // Degenerate and inverted cells, each kind counted once with its first cell's index.
    std::vector<std::string> warnings;
};

// Checks and packs `cells`. Throws std::invalid_argument naming the first problem that makes the field
// unusable: no vertices or cells, counts that disagree, a non-finite position or value, an unknown cell
// type, a cell whose indices run past the index array, an index past the vertices, more than 2^30 indices, or
// no cell with volume. Zero-volume cells are dropped and inverted ones kept, both reported in `warnings`.
std::shared_ptr<const UnstructuredGrid> prepareUnstructuredGrid(const UnstructuredCells& cells);

}  // namespace ripple::core
