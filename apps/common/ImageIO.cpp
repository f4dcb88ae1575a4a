// PNG through stb_image_write (Debian's libstb), PFM by hand: its format is a three-line header and raw floats.
#include "apps/common/ImageIO.h"

#include <stb_image_write.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

namespace {

void checkSize(const std::filesystem::path& file, uint32_t width, uint32_t height, const void* pixels) {
    if (width == 0 || height == 0 || !pixels)
        throw std::runtime_error(file.string() + ": nothing to write (" + std::to_string(width) + "x" +
                                 std::to_string(height) + " image)");
    // stb takes int sizes and strides.
    if (uint64_t(width) * 16 > uint64_t(std::numeric_limits<int>::max()) ||
        uint64_t(height) > uint64_t(std::numeric_limits<int>::max()))
        throw std::runtime_error(file.string() + ": image too large to write");
}

}  // namespace

void writePngBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const uint8_t* rgba) {
    checkSize(file, width, height, rgba);
    // Copied top row first: PNG rows run down the image. (stb's flip switch is global state; a copy is not.)
    const size_t rowBytes = size_t(width) * 4;
    std::vector<uint8_t> topDown(rowBytes * height);
    for (uint32_t y = 0; y < height; ++y)
        std::memcpy(topDown.data() + size_t(height - 1 - y) * rowBytes, rgba + size_t(y) * rowBytes, rowBytes);
    if (!stbi_write_png(file.string().c_str(), int(width), int(height), 4, topDown.data(), int(rowBytes)))
        throw std::runtime_error(file.string() + ": cannot write the PNG");
}

void writePfmBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba) {
    checkSize(file, width, height, rgba);
    std::ofstream out(file, std::ios::binary);
    if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
    // "PF": colour; a negative scale says little-endian.
    out << "PF\n" << width << " " << height << "\n-1.0\n";
    std::vector<float> row(size_t(width) * 3);
    for (uint32_t y = 0; y < height; ++y) {
        const float* src = rgba + size_t(y) * width * 4;
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) row[size_t(x) * 3 + size_t(c)] = src[size_t(x) * 4 + size_t(c)];
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
    }
    if (!out) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace ripple::apps
