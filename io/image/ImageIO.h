// The project's one image reader and writer: PNG (and JPEG) for 8-bit and PFM or EXR for float pixels, both taking rows as
// ANARI frames map them (row 0 at the bottom of the image); PNG, PFM and EXR read into linear RGB.
#pragma once

#include "io/image/LinearImage.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

// Writes width x height RGBA8 pixels, given bottom row first, as a PNG (whose rows run top to bottom).
// Throws std::runtime_error naming the file when it cannot be written.
void writePngBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const uint8_t* rgba);

// Writes width x height float RGBA pixels, bottom row first, as a little-endian colour PFM. PFM has no
// alpha and stores its rows bottom to top, so alpha is dropped and the rows keep their order.
void writePfmBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba);

// Writes width x height float RGBA pixels, bottom row first, as an OpenEXR file (tinyexr) of 32-bit float
// channels R, G, B, A, rows top to bottom as EXR stores them: linear HDR, bit-exact.
void writeExrBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba);

// One channel of an EXR image: its name ("R", "Z", "normal.X", ...) and its values, one every `stride` floats
// from `values`, rows bottom first.
struct ExrChannel {
    std::string name;
    const float* values = nullptr;
    size_t stride = 1;
    bool half = false;                  // stored as 16-bit half float (else 32-bit float)
};
// An EXR image of any channels (written in name order, as OpenEXR lists them).
void writeExrChannelsBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height,
                              std::vector<ExrChannel> channels);

// Writes width x height LINEAR float RGBA pixels, bottom row first, as an 8-bit sRGB-encoded PNG (colour
// clamped to [0, 1], alpha kept linear), as a device's UFIXED8_RGBA_SRGB channel would be.
void writePngFromLinearBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba);

// Linear float RGBA pixels to 8-bit RGBA as the PNG writer stores them: colour sRGB-encoded and clamped to
// [0, 1], alpha kept linear; NaN gives 0. Rows keep their order.
std::vector<uint8_t> encodeSrgb8(uint32_t width, uint32_t height, const float* rgba);

// The same as an 8-bit sRGB JPEG (quality 95; alpha dropped).
void writeJpegFromLinearBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height,
                                 const float* rgba);

// Reads a PNG (sRGB-decoded to linear), PFM, EXR or Radiance HDR (linear) file into linear RGB, row 0 at the top.
// Throws std::runtime_error naming the file and what is wrong with it.
LinearImage readLinearImage(const std::filesystem::path& file);

}  // namespace ripple::apps
