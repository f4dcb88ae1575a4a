// The image writer round-trips: PNG read back with stb_image must give the exact pixels with rows flipped
// (ANARI's row 0 is the bottom row, a PNG's the top); PFM keeps rows bottom-up and drops alpha, bit-exact.
#include "apps/common/ImageIO.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image.h>

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
