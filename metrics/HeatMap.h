// Per-pixel error maps turned into pictures: values in [0, 1] through the magma colour map.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace ripple::apps {

// The magma colour (sRGB, 8 bits) of a value in [0, 1]; values outside are clamped, NaN is shown as 0.
std::array<uint8_t, 3> magma(float value);

// Writes a width x height map (row 0 at the top, values in [0, 1]) as a magma-coloured PNG.
void writeHeatMap(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<float>& values);

}  // namespace ripple::apps
