// The image writer round-trips: PNG read back with stb_image must give the exact pixels with rows flipped
// (ANARI's row 0 is the bottom row, a PNG's the top); PFM keeps rows bottom-up and drops alpha, bit-exact.
// The reader: PNG (sRGB-decoded), PFM (both byte orders, colour and grey) and EXR back to linear RGB, top row
// first, and malformed files refused with the file and the fault named.
#include "io/image/ImageIO.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

using namespace ripple::test;

TEST_CASE("PNG: written bottom-up, read back top-down, exact pixels") {
    TempFolder dir;
    constexpr uint32_t w = 5, h = 3;
    std::vector<uint8_t> bottomUp(w * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (uint32_t c = 0; c < 4; ++c) bottomUp[(y * w + x) * 4 + c] = uint8_t(y * 60 + x * 11 + c * 3);
    const auto file = dir / "round.png";
    ripple::apps::writePngBottomUp(file, w, h, bottomUp.data());

    int rw = 0, rh = 0, comp = 0;
    unsigned char* read = stbi_load(file.string().c_str(), &rw, &rh, &comp, 4);
    REQUIRE(read != nullptr);
    CHECK(rw == int(w));
    CHECK(rh == int(h));
    CHECK(comp == 4);
    int mismatches = 0;
    for (uint32_t y = 0; y < h; ++y)  // file row y is ANARI row h - 1 - y
        mismatches += std::memcmp(read + y * w * 4, bottomUp.data() + (h - 1 - y) * w * 4, w * 4) != 0;
    stbi_image_free(read);
    CHECK(mismatches == 0);
}

TEST_CASE("PFM: header, bottom-up rows, alpha dropped, bit-exact floats") {
    TempFolder dir;
    constexpr uint32_t w = 3, h = 2;
    std::vector<float> rgba(w * h * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = 0.125f * float(i) - 1.0f;
    const auto file = dir / "round.pfm";
    ripple::apps::writePfmBottomUp(file, w, h, rgba.data());

    std::ifstream in(file, std::ios::binary);
    std::string magic, scale;
    uint32_t rw = 0, rh = 0;
    in >> magic >> rw >> rh >> scale;
    in.get();  // the single whitespace byte before the data
    CHECK(magic == "PF");
    CHECK(rw == w);
    CHECK(rh == h);
    CHECK(scale == "-1.0");  // little-endian
    std::vector<float> rgb(w * h * 3);
    in.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
    REQUIRE(in.gcount() == std::streamsize(rgb.size() * sizeof(float)));
    CHECK(in.peek() == std::char_traits<char>::eof());
    int mismatches = 0;
    for (size_t p = 0; p < size_t(w * h); ++p)
        for (size_t c = 0; c < 3; ++c) mismatches += rgb[p * 3 + c] != rgba[p * 4 + c];
    CHECK(mismatches == 0);
}

TEST_CASE("image writer errors name the file") {
    const std::vector<uint8_t> pixel(4, 0);
    CHECK_THROWS_WITH(ripple::apps::writePngBottomUp("/nonexistent-folder/x.png", 1, 1, pixel.data()),
                      doctest::Contains("/nonexistent-folder/x.png"));
    CHECK_THROWS_WITH(ripple::apps::writePngBottomUp("empty.png", 0, 1, pixel.data()), doctest::Contains("nothing to write"));
}

namespace {

float srgbEncode(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f; }

// Bottom-up RGBA floats whose every value differs, so a flipped row or swapped channel shows.
std::vector<float> rampRgba(uint32_t width, uint32_t height, float scale) {
    std::vector<float> rgba(size_t(width) * height * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = scale * float(i + 1) / float(rgba.size());
    return rgba;
}

// The reader's pixel (x, y from the top) against the writer's bottom-up RGBA input.
float writtenAt(const std::vector<float>& rgba, uint32_t width, uint32_t height, uint32_t x, uint32_t y, int c) {
    return rgba[(size_t(height - 1 - y) * width + x) * 4 + size_t(c)];
}

std::vector<uint8_t> pfmBytes(const std::string& header, const std::vector<float>& samples, bool bigEndian) {
    std::vector<uint8_t> bytes(header.begin(), header.end());
    for (float v : samples) {
        auto word = std::bit_cast<uint32_t>(v);
        for (int b = 0; b < 4; ++b) bytes.push_back(uint8_t(word >> (bigEndian ? 24 - 8 * b : 8 * b)));
    }
    return bytes;
}

}  // namespace

TEST_CASE("PNG from linear: sRGB-encoded to 8 bits, read back linear within half a code value, rows flipped") {
    TempFolder dir;
    constexpr uint32_t w = 6, h = 4;
    std::vector<float> rgba = rampRgba(w, h, 1.0f);
    rgba[0] = -0.5f;  // clamped to 0
    rgba[5] = 3.0f;   // clamped to 1
    const auto file = dir / "linear.png";
    ripple::apps::writePngFromLinearBottomUp(file, w, h, rgba.data());
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    REQUIRE(image.width == w);
    REQUIRE(image.height == h);
    double worst = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float written = std::clamp(writtenAt(rgba, w, h, x, y, c), 0.0f, 1.0f);
                worst = std::max(worst, double(std::abs(srgbEncode(image.at(x, y, c)) - srgbEncode(written))));
            }
    CHECK(worst <= 0.5 / 255 + 1e-6);
    CHECK(image.at(0, h - 1, 0) == 0.0f);
    CHECK(image.at(1, h - 1, 1) == doctest::Approx(1.0f));
}

TEST_CASE("PFM: written then read back bit-exact, top row first") {
    TempFolder dir;
    constexpr uint32_t w = 5, h = 3;
    const std::vector<float> rgba = rampRgba(w, h, 1000.0f);
    const auto file = dir / "round.pfm";
    ripple::apps::writePfmBottomUp(file, w, h, rgba.data());
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    REQUIRE(image.width == w);
    REQUIRE(image.height == h);
    int mismatches = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) mismatches += image.at(x, y, c) != writtenAt(rgba, w, h, x, y, c);
    CHECK(mismatches == 0);
}

TEST_CASE("PFM: big-endian colour, grey in both byte orders, scale magnitude multiplies") {
    TempFolder dir;
    // 2x2, file rows bottom first: bottom row (1, 2), top row (3, 4) in grey.
    const std::vector<float> grey = {1, 2, 3, 4};
    for (bool bigEndian : {false, true}) {
        CAPTURE(bigEndian);
        const auto file = writeBytes(dir / "grey.pfm", pfmBytes(bigEndian ? "Pf\n2 2\n2.0\n" : "Pf\n2 2\n-2.0\n", grey, bigEndian));
        const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
        REQUIRE(image.width == 2);
        CHECK(image.at(0, 0, 0) == 6.0f);  // top-left: file's second row, times |scale| 2
        CHECK(image.at(1, 0, 2) == 8.0f);
        CHECK(image.at(0, 1, 1) == 2.0f);
    }
    const std::vector<float> colour = {0.5f, 1.5f, 2.5f};
    const auto file = writeBytes(dir / "big.pfm", pfmBytes("PF\n1 1\n1.0\n", colour, true));
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    CHECK(image.rgb == colour);
}

TEST_CASE("EXR: 32-bit float written by tinyexr read back exact") {
    TempFolder dir;
    constexpr int w = 4, h = 3;
    std::vector<float> rgb(size_t(w * h * 3));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.37f * float(i) + 100.0f * float(i % 3);
    const auto file = dir / "round.exr";
    const char* error = nullptr;
    REQUIRE(SaveEXR(rgb.data(), w, h, 3, 0, file.string().c_str(), &error) == TINYEXR_SUCCESS);
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    REQUIRE(image.width == uint32_t(w));
    REQUIRE(image.height == uint32_t(h));
    CHECK(image.rgb == rgb);
}

TEST_CASE("Radiance HDR: read as linear RGB, top row first, within RGBE's precision") {
    TempFolder dir;
    constexpr int w = 4, h = 2;
    std::vector<float> rgb(size_t(w * h * 3));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.01f + 3.7f * float(i);  // 0.01 .. 85: high dynamic range
    const auto file = dir / "sky.hdr";
    REQUIRE(stbi_write_hdr(file.string().c_str(), w, h, 3, rgb.data()) != 0);
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    REQUIRE(image.width == uint32_t(w));
    REQUIRE(image.height == uint32_t(h));
    for (size_t i = 0; i < rgb.size(); ++i) {
        // RGBE shares one exponent per pixel: each channel within 1/128 of the pixel's largest.
        const size_t pixel = i / 3 * 3;
        const float largest = std::max({rgb[pixel], rgb[pixel + 1], rgb[pixel + 2]});
        CHECK(std::abs(image.rgb[i] - rgb[i]) <= largest / 128.0f);
    }
}

TEST_CASE("EXR: written bottom-up as 32-bit float RGBA, read back exact with the top row first") {
    TempFolder dir;
    constexpr uint32_t w = 5, h = 3;
    std::vector<float> rgba(size_t(w) * h * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = 0.37f * float(i) + 1000.0f * float(i % 4 == 0);  // HDR values
    const auto file = dir / "written.exr";
    ripple::apps::writeExrBottomUp(file, w, h, rgba.data());
    const ripple::apps::LinearImage image = ripple::apps::readLinearImage(file);
    REQUIRE(image.width == w);
    REQUIRE(image.height == h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (uint32_t c = 0; c < 3; ++c)  // image row y is the written row h - 1 - y
                CHECK(image.rgb[(size_t(y) * w + x) * 3 + c] == rgba[(size_t(h - 1 - y) * w + x) * 4 + c]);
    CHECK_THROWS_WITH_AS(ripple::apps::writeExrBottomUp(dir / "no-such-folder" / "x.exr", w, h, rgba.data()),
                         doctest::Contains("x.exr"), std::runtime_error);
}

TEST_CASE("image reader: missing and malformed files are named with their fault") {
    TempFolder dir;
    CHECK_THROWS_WITH(ripple::apps::readLinearImage(dir / "absent.png"), doctest::Contains("no such file"));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"GIF89a", "not a PNG, PFM, EXR or Radiance HDR"},
        {"", "not a PNG, PFM, EXR or Radiance HDR"},
        {"\x89PNG\r\n\x1a\nnot really", "malformed image: PNG"},
        {std::string("\x76\x2f\x31\x01", 4) + "junk", "malformed image: EXR"},
        {"PF\n", "header ends early"},
        {"PF\nabc 2\n-1.0\n", "width 'abc'"},
        {"PF\n2 -2\n-1.0\n", "height '-2'"},
        {"PF\n2 0\n-1.0\n", "height '0'"},
        {"PF\n2 2\n0\n", "scale '0'"},
        {"PF\n2 2\nnan\n", "scale 'nan'"},
        {"PF\n2 2\n-1.0\n" + std::string(47, '\0'), "needs 48 bytes, the file has 47"},
        {"PF\n99999999 2\n-1.0\n", "not a size"},
    };
    for (const auto& [content, message] : cases) {
        CAPTURE(content);
        const auto file = writeBytes(dir / "bad.img", std::vector<uint8_t>(content.begin(), content.end()));
        CHECK_THROWS_WITH(ripple::apps::readLinearImage(file), doctest::Contains(message.c_str()));
        CHECK_THROWS_WITH(ripple::apps::readLinearImage(file), doctest::Contains("bad.img"));
    }
}
