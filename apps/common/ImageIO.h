// The project's one image writer: PNG for RGBA8 and PFM for float pixels, both taking rows as ANARI frames
// map them (row 0 at the bottom of the image).
#pragma once

#include <cstdint>
#include <filesystem>

namespace ripple::apps {

// Writes width x height RGBA8 pixels, given bottom row first, as a PNG (whose rows run top to bottom).
// Throws std::runtime_error naming the file when it cannot be written.
void writePngBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const uint8_t* rgba);

// Writes width x height float RGBA pixels, bottom row first, as a little-endian colour PFM. PFM has no
// alpha and stores its rows bottom to top, so alpha is dropped and the rows keep their order.
void writePfmBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba);

}  // namespace ripple::apps
