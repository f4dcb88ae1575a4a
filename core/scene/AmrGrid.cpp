// Checking and packing an AMR hierarchy (see AmrGrid.h).
#include "core/scene/AmrGrid.h"

#include "shaders/shared/volume.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

using glm::dvec3;

// Index coordinates are kept within +-2^24, where float and double agree on them and on their products with
// a level's cell width.
constexpr int kMaxIndex = 1 << 24;
// The most macrocells and list entries the grid may have (the macrocells grow coarser until they fit).
constexpr uint64_t kMaxMacrocells = uint64_t(1) << 21;
constexpr uint64_t kMaxEntries = uint64_t(1) << 28;

std::string boxText(const glm::ivec3& lo, const glm::ivec3& hi) {
    return "[" + std::to_string(lo.x) + " " + std::to_string(lo.y) + " " + std::to_string(lo.z) + " .. " +
           std::to_string(hi.x) + " " + std::to_string(hi.y) + " " + std::to_string(hi.z) + "]";
}

std::string blockName(size_t index, const AmrBlock& block) {
    return "block " + std::to_string(index) + " (level " + std::to_string(block.level) + ")";
}

void widen(glm::vec2& range, float value) { range = glm::vec2(std::min(range.x, value), std::max(range.y, value)); }

void checkBlocks(const AmrHierarchy& h) {
    if (h.cellWidth.empty()) throw std::invalid_argument("no cell width (one per level) is given");
    if (h.blocks.empty()) throw std::invalid_argument("the hierarchy has no block");
    for (size_t l = 0; l < h.cellWidth.size(); ++l) {
        if (!std::isfinite(h.cellWidth[l]) || h.cellWidth[l] <= 0.0f)
            throw std::invalid_argument("the cell width of level " + std::to_string(l) + " is not finite and positive");
        if (l > 0 && h.cellWidth[l] >= h.cellWidth[l - 1])
            throw std::invalid_argument("the cell width of level " + std::to_string(l) + " (" + std::to_string(h.cellWidth[l]) +
                                        ") is not below level " + std::to_string(l - 1) + "'s (" +
                                        std::to_string(h.cellWidth[l - 1]) + ")");
    }
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(h.origin[a]) || !std::isfinite(h.spacing[a]) || h.spacing[a] <= 0.0f)
            throw std::invalid_argument("the origin must be finite and the spacing finite and positive");
    uint64_t cells = 0;
    for (size_t b = 0; b < h.blocks.size(); ++b) {
        const AmrBlock& block = h.blocks[b];
        if (block.level >= h.cellWidth.size())
            throw std::invalid_argument(blockName(b, block) + " has no cell width: " + std::to_string(h.cellWidth.size()) +
                                        " levels are given");
        for (int a = 0; a < 3; ++a) {
            if (block.lower[a] > block.upper[a])
                throw std::invalid_argument(blockName(b, block) + " has an empty box " + boxText(block.lower, block.upper));
            if (block.lower[a] < -kMaxIndex || block.upper[a] >= kMaxIndex)
                throw std::invalid_argument(blockName(b, block) + "'s box " + boxText(block.lower, block.upper) +
                                            " reaches past +-2^24");
        }
        const glm::u64vec3 dims = glm::u64vec3(glm::i64vec3(block.upper) - glm::i64vec3(block.lower) + int64_t(1));
        const uint64_t count = dims.x * dims.y * dims.z;
        if (count > kMaxAmrCells || (cells += count) > kMaxAmrCells)
            throw std::invalid_argument("the hierarchy has more than 2^30 cells");
        if (block.values.size() != count)
            throw std::invalid_argument(blockName(b, block) + " has " + std::to_string(block.values.size()) + " values for its " +
                                        std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) +
                                        " cells");
        for (size_t i = 0; i < block.values.size(); ++i)
            if (!std::isfinite(block.values[i]))
                throw std::invalid_argument(blockName(b, block) + " value " + std::to_string(i) + " is not finite");
    }
}

// A block's box in level units (object = origin + spacing * level units): cell i of level l spans
// [i, i + 1] * cellWidth[l].
struct LevelBox {
    dvec3 lo, hi;
};

LevelBox levelBox(const AmrHierarchy& h, const AmrBlock& block) {
    const double w = h.cellWidth[block.level];
    return {dvec3(block.lower) * w, (dvec3(block.upper) + 1.0) * w};
}

}  // namespace

std::shared_ptr<const AmrGrid> prepareAmrGrid(const AmrHierarchy& h) {
    checkBlocks(h);
    auto grid = std::make_shared<AmrGrid>();

    // The box of the coarsest level present holds every block.
    uint32_t coarsest = UINT32_MAX, finest = 0;
    for (const AmrBlock& block : h.blocks) {
        coarsest = std::min(coarsest, block.level);
        finest = std::max(finest, block.level);
    }
    LevelBox domain{dvec3(INFINITY), dvec3(-INFINITY)};
    for (const AmrBlock& block : h.blocks)
        if (block.level == coarsest) {
            const LevelBox box = levelBox(h, block);
            domain = {glm::min(domain.lo, box.lo), glm::max(domain.hi, box.hi)};
        }
    const double slack = 1e-6 * std::max(1.0, glm::length(domain.hi - domain.lo));
    for (size_t b = 0; b < h.blocks.size(); ++b) {
        const LevelBox box = levelBox(h, h.blocks[b]);
        if (glm::any(glm::lessThan(box.lo, domain.lo - slack)) || glm::any(glm::greaterThan(box.hi, domain.hi + slack)))
            throw std::invalid_argument(blockName(b, h.blocks[b]) + "'s box " + boxText(h.blocks[b].lower, h.blocks[b].upper) +
                                        " lies outside the box of level " + std::to_string(coarsest) + "'s blocks");
    }
    std::vector<uint32_t> levelsUsed(h.cellWidth.size(), 0u);
    for (const AmrBlock& block : h.blocks) levelsUsed[block.level] = 1u;
    for (uint32_t used : levelsUsed) grid->levels += used;

    // Grid space: level units from domain.lo, over a unit of 2^k finest cells, the smallest k whose macrocells
    // (VOLUME_MACROCELL units a side) number at most kMaxMacrocells.
    const dvec3 extent = domain.hi - domain.lo;
    double unit = h.cellWidth[finest];
    // In double until they fit: a hostile ratio of cell widths could overflow any integer.
    const auto macrocellsFor = [&](double u) { return glm::max(glm::ceil(extent / (u * double(gpu::VOLUME_MACROCELL))), dvec3(1.0)); };
    for (dvec3 n = macrocellsFor(unit); n.x * n.y * n.z > double(kMaxMacrocells); n = macrocellsFor(unit)) unit *= 2.0;
    grid->macrocells = glm::uvec3(macrocellsFor(unit));
    const glm::uvec3 m = grid->macrocells;
    const dvec3 objectLo = dvec3(h.origin) + dvec3(h.spacing) * domain.lo;
    grid->lo = glm::vec3(objectLo);
    grid->hi = glm::vec3(dvec3(h.origin) + dvec3(h.spacing) * domain.hi);
    grid->objectToGrid = glm::scale(glm::dmat4(1.0), 1.0 / (dvec3(h.spacing) * unit)) * glm::translate(glm::dmat4(1.0), -objectLo);

    // Each block's macrocells (those its grid-space box overlaps), and the lists per macrocell.
    const size_t macrocellCount = size_t(m.x) * m.y * m.z;
    struct Span {
        glm::uvec3 first, last;
    };
    // Widened by kSlack grid units: the kernels place blocks and find macrocells in float, so a point on a
    // macrocell's face may land on either side of it.
    constexpr double kSlack = 1e-3;
    const auto macrocellSpan = [&](const dvec3& lo, const dvec3& hi) {
        const double side = double(gpu::VOLUME_MACROCELL);
        const glm::ivec3 first = glm::clamp(glm::ivec3(glm::floor((lo - kSlack) / side)), glm::ivec3(0), glm::ivec3(m) - 1);
        const glm::ivec3 last = glm::clamp(glm::ivec3(glm::ceil((hi + kSlack) / side)) - 1, first, glm::ivec3(m) - 1);
        return Span{glm::uvec3(first), glm::uvec3(last)};
    };
    const auto toGrid = [&](const dvec3& levelUnits) { return (levelUnits - domain.lo) / unit; };
    std::vector<uint32_t> counts(macrocellCount, 0u);
    std::vector<Span> spans(h.blocks.size());
    uint64_t entries = 0;
    for (size_t b = 0; b < h.blocks.size(); ++b) {
        const LevelBox box = levelBox(h, h.blocks[b]);
        spans[b] = macrocellSpan(toGrid(box.lo), toGrid(box.hi));
        const glm::uvec3 n = spans[b].last - spans[b].first + 1u;
        entries += uint64_t(n.x) * n.y * n.z;
        if (entries > kMaxEntries) throw std::invalid_argument("the blocks overlap more than 2^28 (block, macrocell) pairs");
        for (uint32_t z = spans[b].first.z; z <= spans[b].last.z; ++z)
            for (uint32_t y = spans[b].first.y; y <= spans[b].last.y; ++y)
                for (uint32_t x = spans[b].first.x; x <= spans[b].last.x; ++x) ++counts[(size_t(z) * m.y + y) * m.x + x];
    }
    // The kernels walk a list in one loop, which lavapipe ends after 65,535 iterations.
    for (size_t c = 0; c < macrocellCount; ++c)
        if (counts[c] > 65535u) throw std::invalid_argument("more than 65,535 blocks overlap one macrocell");
    std::vector<uint32_t> firstEntry(macrocellCount + 1, 0u);
    for (size_t c = 0; c < macrocellCount; ++c) firstEntry[c + 1] = firstEntry[c] + counts[c];
    std::vector<uint32_t> list(entries);
    {
        std::vector<uint32_t> filled(firstEntry.begin(), firstEntry.end() - 1);
        for (size_t b = 0; b < h.blocks.size(); ++b)
            for (uint32_t z = spans[b].first.z; z <= spans[b].last.z; ++z)
                for (uint32_t y = spans[b].first.y; y <= spans[b].last.y; ++y)
                    for (uint32_t x = spans[b].first.x; x <= spans[b].last.x; ++x)
                        list[filled[(size_t(z) * m.y + y) * m.x + x]++] = uint32_t(b);
    }
    // Finest level first; then two blocks of one level in a list are checked for overlap.
    for (size_t c = 0; c < macrocellCount; ++c) {
        const auto begin = list.begin() + firstEntry[c], end = list.begin() + firstEntry[c + 1];
        std::sort(begin, end, [&](uint32_t a, uint32_t b) {
            return h.blocks[a].level != h.blocks[b].level ? h.blocks[a].level > h.blocks[b].level : a < b;
        });
        for (auto a = begin; a != end; ++a)
            for (auto b = a + 1; b != end && h.blocks[*b].level == h.blocks[*a].level; ++b) {
                const AmrBlock &p = h.blocks[*a], &q = h.blocks[*b];
                if (glm::all(glm::lessThanEqual(p.lower, q.upper)) && glm::all(glm::lessThanEqual(q.lower, p.upper)))
                    throw std::invalid_argument(blockName(*a, p) + " " + boxText(p.lower, p.upper) + " and block " +
                                                std::to_string(*b) + " " + boxText(q.lower, q.upper) + " overlap");
            }
    }

    // The words: header, blocks, lists, entries, values.
    const uint32_t headerWords = uint32_t(sizeof(gpu::AmrHeader) / 4);
    const uint64_t blockWords = uint64_t(h.blocks.size()) * (sizeof(gpu::AmrBlockRecord) / 4);
    gpu::AmrHeader header{};
    header.blockCount = uint32_t(h.blocks.size());
    header.blockOffset = headerWords;
    header.listOffset = uint32_t(header.blockOffset + blockWords);
    header.entryOffset = uint32_t(header.listOffset + 2 * uint64_t(macrocellCount));
    uint64_t valueOffset = header.entryOffset + entries;
    std::vector<gpu::AmrBlockRecord> records(h.blocks.size());
    for (size_t b = 0; b < h.blocks.size(); ++b) {
        const AmrBlock& block = h.blocks[b];
        const dvec3 lower = toGrid(levelBox(h, block).lo);
        gpu::AmrBlockRecord& r = records[b];
        r.lowerX = float(lower.x);
        r.lowerY = float(lower.y);
        r.lowerZ = float(lower.z);
        r.cellSize = float(double(h.cellWidth[block.level]) / unit);
        r.dimX = uint32_t(block.upper.x - block.lower.x + 1);
        r.dimY = uint32_t(block.upper.y - block.lower.y + 1);
        r.dimZ = uint32_t(block.upper.z - block.lower.z + 1);
        r.firstValue = uint32_t(valueOffset);
        valueOffset += block.values.size();
        if (valueOffset > UINT32_MAX) throw std::invalid_argument("the hierarchy is larger than the kernels' 32-bit addressing");
    }
    grid->words.resize(valueOffset);
    std::memcpy(grid->words.data(), &header, sizeof header);
    std::memcpy(grid->words.data() + header.blockOffset, records.data(), records.size() * sizeof(gpu::AmrBlockRecord));
    for (size_t c = 0; c < macrocellCount; ++c) {
        grid->words[header.listOffset + 2 * c] = firstEntry[c];
        grid->words[header.listOffset + 2 * c + 1] = counts[c];
    }
    std::copy(list.begin(), list.end(), grid->words.begin() + header.entryOffset);

    // Values, and the range per macrocell of the cells overlapping it (each cell's own span of macrocells).
    grid->macrocellRanges.assign(macrocellCount, glm::vec2(INFINITY, -INFINITY));
    grid->valueRange = glm::vec2(INFINITY, -INFINITY);
    for (size_t b = 0; b < h.blocks.size(); ++b) {
        const AmrBlock& block = h.blocks[b];
        const gpu::AmrBlockRecord& r = records[b];
        std::memcpy(grid->words.data() + r.firstValue, block.values.data(), block.values.size() * sizeof(float));
        const dvec3 lower = toGrid(levelBox(h, block).lo);
        const double side = double(h.cellWidth[block.level]) / unit;
        size_t i = 0;
        for (uint32_t z = 0; z < r.dimZ; ++z)
            for (uint32_t y = 0; y < r.dimY; ++y)
                for (uint32_t x = 0; x < r.dimX; ++x, ++i) {
                    const float value = block.values[i];
                    widen(grid->valueRange, value);
                    const dvec3 cellLo = lower + dvec3(x, y, z) * side;
                    const Span s = macrocellSpan(cellLo, cellLo + side);
                    for (uint32_t mz = s.first.z; mz <= s.last.z; ++mz)
                        for (uint32_t my = s.first.y; my <= s.last.y; ++my)
                            for (uint32_t mx = s.first.x; mx <= s.last.x; ++mx)
                                widen(grid->macrocellRanges[(size_t(mz) * m.y + my) * m.x + mx], value);
                }
        grid->cells += block.values.size();
    }
    return grid;
}

}  // namespace ripple::core
