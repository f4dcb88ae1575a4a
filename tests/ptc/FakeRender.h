// The colors and depths the test double device renders on each rank, shared by the double and the test
// that predicts the composited image. All values are dyadic so compositing them is exact in float.
#pragma once

#include <cmath>
#include <cstdint>

namespace fakerender {

inline constexpr const char* kRenderedMessage = "ptcfake rendered";

struct Fragment {
    float rgba[4];  // premultiplied
    float depth;
};

// Pixel (x, y) on rank `rank`: every fifth pixel is background (rank 0's is a translucent blue, the
// others' empty); the rest have depths whose order changes with the rank, half of them half transparent.
inline Fragment fragment(uint32_t x, uint32_t y, int rank) {
    const uint32_t k = (x + 2 * y + 3 * uint32_t(rank)) % 5;
    if (k == 4) {
        if (rank == 0) return {{0.0f, 0.0f, 0.125f, 0.25f}, INFINITY};
        return {{0.0f, 0.0f, 0.0f, 0.0f}, INFINITY};
    }
    const float alpha = k % 2 == 0 ? 0.5f : 1.0f;
    const float depth = 1.0f + float((k + 2 * uint32_t(rank)) % 4) + 0.25f * float(rank);
    return {{alpha * 0.25f * float(rank + 1), alpha * 0.5f, alpha * 0.125f * float(k), alpha}, depth};
}

}  // namespace fakerender
