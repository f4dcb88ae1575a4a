// Splitting an AMR hierarchy over ranks (see AmrPartition.h).
#include "apps/scene/AmrPartition.h"

#include "apps/scene/KdSplit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ripple::apps {

namespace {

// Boxes in cells of the coarsest level: [lo, hi), the cells between planes lo and hi.
using Region = KdBox;

// How many cells of one coarse cell's width a level's cell is: coarse / width, a whole number (checked).
std::vector<int64_t> levelRatios(const AmrData& whole, uint32_t coarsest) {
    std::vector<int64_t> ratios(whole.cellWidth.size(), 0);
    for (size_t l = coarsest; l < whole.cellWidth.size(); ++l) {
        const double ratio = double(whole.cellWidth[coarsest]) / double(whole.cellWidth[l]);
        ratios[l] = ratio >= 1.0 && ratio <= double(1 << 24) ? std::llround(ratio) : 0;
        if (ratios[l] < 1 || std::abs(ratio - double(ratios[l])) > 1e-4 * ratio)
            throw std::runtime_error("level " + std::to_string(l) + "'s cell width does not divide level " +
                                     std::to_string(coarsest) + "'s a whole number of times, so the hierarchy cannot be split "
                                     "along its cells");
    }
    return ratios;
}

// The part of `block` in `region` (in its own level's cells), as lower..upper inclusive; empty when hi < lo.
std::pair<glm::i64vec3, glm::i64vec3> clipped(const AmrData::Block& block, const Region& region, int64_t ratio) {
    const glm::i64vec3 lo = glm::max(glm::i64vec3(block.lower), region.lo * ratio);
    const glm::i64vec3 hi = glm::min(glm::i64vec3(block.upper), region.hi * ratio - int64_t(1));
    return {lo, hi};
}

uint64_t cellsIn(const AmrData& whole, const std::vector<int64_t>& ratios, const Region& region) {
    uint64_t cells = 0;
    for (const AmrData::Block& block : whole.blocks) {
        const auto [lo, hi] = clipped(block, region, ratios[block.level]);
        if (glm::all(glm::lessThanEqual(lo, hi))) {
            const glm::i64vec3 n = hi - lo + int64_t(1);
            cells += uint64_t(n.x * n.y * n.z);
        }
    }
    return cells;
}

}  // namespace

AmrData amrPart(const AmrData& whole, uint32_t rank, uint32_t ranks) {
    if (ranks <= 1) return whole;
    uint32_t coarsest = UINT32_MAX;
    for (const AmrData::Block& block : whole.blocks) coarsest = std::min(coarsest, block.level);
    const std::vector<int64_t> ratios = levelRatios(whole, coarsest);
    Region domain{glm::i64vec3(INT64_MAX), glm::i64vec3(INT64_MIN)};
    for (const AmrData::Block& block : whole.blocks) {
        const int64_t r = ratios[block.level];
        // Coarse cells the block touches (floor of its lower face, ceiling of its upper).
        const glm::i64vec3 lo = glm::i64vec3(glm::floor(glm::dvec3(block.lower) / double(r)));
        const glm::i64vec3 hi = glm::i64vec3(glm::ceil((glm::dvec3(block.upper) + 1.0) / double(r)));
        domain = {glm::min(domain.lo, lo), glm::max(domain.hi, hi)};
    }
    const Region region = kdRegion(domain, rank, ranks, [&](const Region& r) { return double(cellsIn(whole, ratios, r)); });

    AmrData part;
    part.origin = whole.origin;
    part.spacing = whole.spacing;
    part.cellWidth = whole.cellWidth;
    part.arrayName = whole.arrayName;
    part.minValue = whole.minValue;
    part.maxValue = whole.maxValue;
    for (const AmrData::Block& block : whole.blocks) {
        const auto [lo, hi] = clipped(block, region, ratios[block.level]);
        if (glm::any(glm::greaterThan(lo, hi))) continue;
        AmrData::Block& kept = part.blocks.emplace_back();
        kept.level = block.level;
        kept.lower = glm::ivec3(lo);
        kept.upper = glm::ivec3(hi);
        const glm::i64vec3 dims = glm::i64vec3(block.upper - block.lower) + int64_t(1), from = lo - glm::i64vec3(block.lower);
        for (int64_t z = lo.z; z <= hi.z; ++z)
            for (int64_t y = lo.y; y <= hi.y; ++y) {
                const int64_t row = ((z - block.lower.z) * dims.y + (y - block.lower.y)) * dims.x + from.x;
                kept.values.insert(kept.values.end(), block.values.begin() + row, block.values.begin() + row + (hi.x - lo.x + 1));
            }
        part.cells += kept.values.size();
    }
    if (part.blocks.empty())
        throw std::runtime_error("rank " + std::to_string(rank) + "'s region of the hierarchy holds no cell: it cannot be split over " +
                                 std::to_string(ranks) + " ranks");
    return part;
}

std::pair<glm::dvec3, glm::dvec3> amrBounds(const AmrData& amr) {
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const AmrData::Block& block : amr.blocks) {
        const double width = amr.cellWidth.at(block.level);
        lo = glm::min(lo, glm::dvec3(amr.origin) + glm::dvec3(amr.spacing) * glm::dvec3(block.lower) * width);
        hi = glm::max(hi, glm::dvec3(amr.origin) + glm::dvec3(amr.spacing) * (glm::dvec3(block.upper) + 1.0) * width);
    }
    return {lo, hi};
}

}  // namespace ripple::apps
