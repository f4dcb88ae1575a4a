// The tools' in-memory image: linear RGB floats, as the image reader returns them and the metrics compare
// them; and the sRGB transfer curves the reader, the writer and the metrics share.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ripple::apps {

// Linear RGB, row 0 at the TOP of the image, 3 floats a pixel.
struct LinearImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;
    float at(uint32_t x, uint32_t y, int c) const { return rgb[(size_t(y) * width + x) * 3 + size_t(c)]; }
};

namespace detail {

inline float srgbEncode(float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

inline float srgbDecode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace detail
}  // namespace ripple::apps
