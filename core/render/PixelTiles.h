// Which pixels a rank generates and shades in a data-parallel render: the image is cut into bands of
// kTileRows rows, dealt to the ranks round robin, so every rank gets a similar share of every part of the
// image. Row 0 is the bottom row; a band is one contiguous run of pixel indices.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ripple::core {

inline constexpr uint32_t kTileRows = 4;

struct PixelRange {
    uint32_t first = 0;  // y * width + x
    uint32_t count = 0;
};

// The bands `rank` of `rankCount` owns, in image order. One rank owns the whole image as one range.
inline std::vector<PixelRange> ownedPixels(glm::uvec2 size, uint32_t rank, uint32_t rankCount) {
    std::vector<PixelRange> ranges;
    if (rankCount <= 1) {
        ranges.push_back({0, size.x * size.y});
        return ranges;
    }
    for (uint32_t band = rank; band * kTileRows < size.y; band += rankCount) {
        const uint32_t rows = std::min(kTileRows, size.y - band * kTileRows);
        ranges.push_back({band * kTileRows * size.x, rows * size.x});
    }
    return ranges;
}

// One wave of the path tracer: pixel ranges whose paths fill one queue, each at its offset in the queue.
struct WavePart {
    PixelRange pixels;
    uint32_t queueOffset = 0;
};
struct Wave {
    std::vector<WavePart> parts;
    uint32_t paths = 0;
};

// Packs the ranges into waves of at most `capacity` paths, splitting a range where a wave fills up.
inline std::vector<Wave> packWaves(const std::vector<PixelRange>& ranges, uint32_t capacity) {
    std::vector<Wave> waves;
    for (PixelRange range : ranges) {
        while (range.count > 0) {
            if (waves.empty() || waves.back().paths == capacity) waves.emplace_back();
            Wave& wave = waves.back();
            const uint32_t take = std::min(range.count, capacity - wave.paths);
            wave.parts.push_back({{range.first, take}, wave.paths});
            wave.paths += take;
            range.first += take;
            range.count -= take;
        }
    }
    return waves;
}

}  // namespace ripple::core
