// libFuzzer target: what the device checks before a kernel reads a sparse, adaptive or unstructured field, on
// the host and without Vulkan: NanoVDB grid buffers (core/scene/NanoVdbGrid.h, through NanoVdbTree.h's checked
// walk), AMR hierarchies (core/scene/AmrGrid.h) and unstructured meshes (core/scene/UnstructuredGrid.h). The
// input's first byte chooses: even, the rest is a NanoVDB grid buffer; 1 modulo 4, the rest is decoded into a
// hierarchy (levels, cell widths, blocks with boxes, levels and values, any of them wrong); 3 modulo 4, into a
// mesh (vertices on a small lattice, so that cells share faces, cells of any type with any indices, values
// of any kind). Every input must be refused with std::invalid_argument, or prepared with every macrocell range
// ordered or empty and, for a mesh, every word the kernels follow in range: cells' indices, neighbour links
// (mutual, between tetrahedra), start nodes and start tetrahedra. Nothing else may happen.
#include "core/scene/AmrGrid.h"
#include "core/scene/NanoVdbGrid.h"
#include "core/scene/UnstructuredGrid.h"
#include "shaders/shared/bvh.h"
#include "shaders/shared/volume.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace {

// The input as a stream of bytes; past its end every read is 0.
class Input {
public:
    Input(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    int8_t small() { return int8_t(byte()); }
    float number() {
        const uint8_t kind = byte();
        if (kind == 255) {  // raw bits: NaN, infinities, denormals
            uint32_t bits = uint32_t(byte()) | uint32_t(byte()) << 8 | uint32_t(byte()) << 16 | uint32_t(byte()) << 24;
            float f;
            std::memcpy(&f, &bits, sizeof f);
            return f;
        }
        return float(kind) / 16.0f - 4.0f;
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t at_ = 0;
};

void checkRanges(const std::vector<glm::vec2>& ranges) {
    for (const glm::vec2& r : ranges)
        if (!(r.x <= r.y) && !(r.x == INFINITY && r.y == -INFINITY)) std::abort();  // neither ordered nor empty
}

void amr(Input& in) {
    ripple::core::AmrHierarchy h;
    const uint32_t levels = in.byte() % 5;
    float width = 1.0f;
    for (uint32_t l = 0; l < levels; ++l) {
        const uint8_t step = in.byte();
        width = step == 255 ? in.number() : width / float(1 + step % 4);  // mostly halving, sometimes equal or wrong
        h.cellWidth.push_back(width);
    }
    h.origin = glm::vec3(in.number(), in.number(), in.number());
    h.spacing = glm::vec3(in.number(), 0.5f, 0.5f);
    const uint32_t blocks = in.byte() % 9;
    for (uint32_t b = 0; b < blocks; ++b) {
        ripple::core::AmrBlock block;
        block.level = in.byte() % 6;
        for (int a = 0; a < 3; ++a) {
            block.lower[a] = in.small();
            block.upper[a] = block.lower[a] + in.small() % 6;  // may be below lower
        }
        if (in.byte() == 7) block.upper.x = (1 << 25);  // past the index limit
        const glm::ivec3 n = glm::max(block.upper - block.lower + 1, 0);
        const int64_t cells = int64_t(n.x) * n.y * n.z;
        const int64_t count = cells > 4096 ? 4096 : cells + (in.byte() == 3 ? 1 : 0);  // sometimes one too many
        for (int64_t i = 0; i < count; ++i) block.values.push_back(in.number());
        h.blocks.push_back(std::move(block));
    }
    try {
        const auto grid = ripple::core::prepareAmrGrid(h);
        checkRanges(grid->macrocellRanges);
    } catch (const std::invalid_argument&) {
    }
}

void require(bool holds) {
    if (!holds) std::abort();
}

// The packed words as the kernels read them (shaders/unstructured.glsl): every offset and link in range.
void checkMeshWords(const ripple::core::UnstructuredGrid& grid) {
    namespace gpu = ripple::gpu;
    const std::vector<uint32_t>& w = grid.words;
    require(w.size() * sizeof(uint32_t) >= sizeof(gpu::UnstructuredHeader));
    gpu::UnstructuredHeader h;
    std::memcpy(&h, w.data(), sizeof h);
    const uint64_t starts = uint64_t(h.startX) * h.startY * h.startZ;
    require(h.vertexOffset % 4 == 0 && h.vertexOffset <= h.cellValueOffset && h.cellOffset + uint64_t(h.cellCount) <= h.indexOffset &&
            h.indexOffset <= h.nodeOffset && h.nodeOffset + uint64_t(h.nodeCount) * sizeof(gpu::BvhNode) / 4 <= h.startOffset &&
            h.startOffset + starts <= w.size() && (!h.neighbours || h.startCellOffset + starts <= w.size()) && h.startPerMacrocell >= 1);
    const uint64_t vertices = (uint64_t(h.cellValueOffset) - h.vertexOffset) / 4;
    require(h.neighbours <= gpu::UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA);
    const uint32_t corners[4] = {4, 8, 6, 5};
    for (uint32_t c = 0; c < h.cellCount; ++c) {
        const uint32_t word = w[h.cellOffset + c], shape = word & 3u;
        const uint64_t first = uint64_t(h.indexOffset) + (word >> 2);
        // A mesh of tetrahedra only: the walk takes cell c's words at 8c without reading its word.
        if (h.neighbours == gpu::UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA) require(shape == gpu::UNSTRUCTURED_TETRAHEDRON && (word >> 2) == 8ull * c);
        const uint64_t end = first + corners[shape] + (h.neighbours && shape == gpu::UNSTRUCTURED_TETRAHEDRON ? 4 : 0);
        require(end <= h.nodeOffset);
        for (uint32_t k = 0; k < corners[shape]; ++k) require(w[first + k] < vertices);
        if (!h.neighbours || shape != gpu::UNSTRUCTURED_TETRAHEDRON) continue;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t other = w[first + 4 + k];
            if (other == gpu::UNSTRUCTURED_NO_CELL) continue;
            require(other < h.cellCount && (w[h.cellOffset + other] & 3u) == gpu::UNSTRUCTURED_TETRAHEDRON);
            const uint64_t otherFirst = uint64_t(h.indexOffset) + (w[h.cellOffset + other] >> 2);
            bool back = false;
            for (uint32_t j = 0; j < 4; ++j) back = back || w[otherFirst + 4 + j] == c;
            require(back);
            // The face opposite corner k: its 3 vertices are corners of the neighbour too.
            for (uint32_t j = 1; j < 4; ++j) {
                const uint32_t v = w[first + (k + j) % 4];
                require(v == w[otherFirst] || v == w[otherFirst + 1] || v == w[otherFirst + 2] || v == w[otherFirst + 3]);
            }
        }
    }
    for (uint64_t i = 0; i < starts; ++i) {
        const uint32_t node = w[h.startOffset + i];
        require(node == gpu::UNSTRUCTURED_NO_NODE || node < h.nodeCount);
        if (!h.neighbours) continue;
        const uint32_t cell = w[h.startCellOffset + i];
        require(cell == gpu::UNSTRUCTURED_NO_CELL || (cell < h.cellCount && (w[h.cellOffset + cell] & 3u) == gpu::UNSTRUCTURED_TETRAHEDRON));
    }
}

void mesh(Input& in) {
    ripple::core::UnstructuredCells cells;
    const uint32_t vertices = 1 + in.byte() % 24;
    for (uint32_t v = 0; v < vertices; ++v) {
        const uint8_t kind = in.byte();
        // Mostly lattice points of a 3 x 3 x 3 box (shared faces), sometimes any number (NaN, huge, tiny).
        cells.positions.push_back(kind < 240 ? glm::vec3(kind % 3, kind / 3 % 3, kind / 9 % 3)
                                             : glm::vec3(in.number(), in.number(), in.number()));
    }
    const uint8_t types[6] = {10, 10, 12, 13, 14, 11};
    const uint32_t count = in.byte() % 24;
    for (uint32_t c = 0; c < count; ++c) {
        const uint8_t type = types[in.byte() % 6];
        cells.cellType.push_back(type);
        cells.cellIndex.push_back(in.byte() == 9 ? uint32_t(cells.index.size()) + 5 : uint32_t(cells.index.size()));
        for (uint32_t k = 0; k < std::max(ripple::core::unstructuredCorners(type), 4u); ++k) {
            const uint8_t i = in.byte();
            cells.index.push_back(i == 255 ? vertices : i % vertices);  // sometimes one past the vertices
        }
    }
    cells.cellCentered = in.byte() % 2 == 1;
    const size_t values = (cells.cellCentered ? count : vertices) + (in.byte() == 5 ? 1 : 0);  // sometimes one too many
    for (size_t i = 0; i < values; ++i) cells.values.push_back(in.number());
    try {
        const auto grid = ripple::core::prepareUnstructuredGrid(cells);
        checkRanges(grid->macrocellRanges);
        checkMeshWords(*grid);
    } catch (const std::invalid_argument&) {
    }
}

void nanovdb(const uint8_t* data, size_t size) {
    try {
        const auto grid = ripple::core::prepareNanoVdbGrid(std::span<const uint8_t>(data, size));
        checkRanges(grid->macrocellRanges);
    } catch (const std::invalid_argument&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) { return 0; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    Input in(data + 1, size - 1);
    if (data[0] % 2 == 0) nanovdb(data + 1, size - 1);
    else if (data[0] % 4 == 1) amr(in);
    else mesh(in);
    return 0;
}
