// k-d split of an unstructured mesh's cells among ranks (see MeshPartition.h).
#include "apps/scene/MeshPartition.h"

#include <algorithm>
#include <numeric>
#include <span>

namespace ripple::apps {

namespace {

// Narrows `cells` (indices into the mesh, centroids alongside) to `rank`'s part among `ranks`: the longest
// axis of their centroids' box is split where the counts are in proportion to the ranks on each side.
void narrow(std::vector<uint32_t>& cells, const std::vector<glm::vec3>& centroids, uint32_t rank, uint32_t ranks) {
    std::span<uint32_t> part(cells);
    while (ranks > 1) {
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (uint32_t c : part) {
            lo = glm::min(lo, centroids[c]);
            hi = glm::max(hi, centroids[c]);
        }
        const glm::vec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        const uint32_t leftRanks = ranks / 2;
        const size_t split = part.size() * leftRanks / ranks;
        // Ties broken by cell index, so every rank computes the same split.
        std::nth_element(part.begin(), part.begin() + std::ptrdiff_t(split), part.end(), [&](uint32_t a, uint32_t b) {
            return centroids[a][axis] != centroids[b][axis] ? centroids[a][axis] < centroids[b][axis] : a < b;
        });
        if (rank < leftRanks) {
            part = part.first(split);
            ranks = leftRanks;
        } else {
            part = part.subspan(split);
            rank -= leftRanks;
            ranks -= leftRanks;
        }
    }
    std::vector<uint32_t> kept(part.begin(), part.end());
    std::sort(kept.begin(), kept.end());
    cells = std::move(kept);
}

}  // namespace

UnstructuredMesh meshPart(const UnstructuredMesh& whole, uint32_t rank, uint32_t ranks) {
    if (ranks <= 1) return whole;
    const size_t cellCount = whole.cellType.size();
    std::vector<glm::vec3> centroids(cellCount);
    for (size_t c = 0; c < cellCount; ++c) {
        glm::vec3 sum(0.0f);
        const uint32_t corners = linearCellCorners(whole.cellType[c]);
        for (uint32_t k = 0; k < corners; ++k) sum += whole.positions[whole.index[whole.cellIndex[c] + k]];
        centroids[c] = sum / float(corners);
    }
    std::vector<uint32_t> cells(cellCount);
    std::iota(cells.begin(), cells.end(), 0u);
    narrow(cells, centroids, rank, ranks);

    UnstructuredMesh part;
    part.fieldName = whole.fieldName;
    part.cellCentered = whole.cellCentered;
    part.minValue = whole.minValue;
    part.maxValue = whole.maxValue;
    part.warnings = whole.warnings;
    std::vector<uint32_t> newIndex(whole.positions.size(), UINT32_MAX);
    for (uint32_t c : cells) {
        part.cellIndex.push_back(uint32_t(part.index.size()));
        part.cellType.push_back(whole.cellType[c]);
        if (whole.cellCentered) part.values.push_back(whole.values[c]);
        const uint32_t corners = linearCellCorners(whole.cellType[c]);
        for (uint32_t k = 0; k < corners; ++k) {
            const uint32_t v = whole.index[whole.cellIndex[c] + k];
            if (newIndex[v] == UINT32_MAX) {
                newIndex[v] = uint32_t(part.positions.size());
                part.positions.push_back(whole.positions[v]);
                if (!whole.cellCentered) part.values.push_back(whole.values[v]);
            }
            part.index.push_back(newIndex[v]);
        }
    }
    return part;
}

}  // namespace ripple::apps
