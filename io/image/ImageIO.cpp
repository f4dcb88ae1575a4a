// PNG through stb_image / stb_image_write (Debian's libstb), EXR through tinyexr, PFM by hand: its format is a
// three-line header and raw floats. Readers tell the format from the file's first bytes, not its name.
#include "io/image/ImageIO.h"

#include "io/FileRead.h"
#include "io/FileWrite.h"
#include "io/image/LinearImage.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
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

using detail::srgbDecode;
using detail::srgbEncode;

// stb's writers hand their output to a callback: it is collected here, then written in one piece.
void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

std::runtime_error malformed(const std::filesystem::path& file, const std::string& what) {
    return std::runtime_error(file.string() + ": malformed image: " + what);
}

// 8- and 16-bit PNGs alike: stb widens 8-bit samples to 16 bits exactly (v * 257), so one path serves both.
LinearImage readPng(const std::filesystem::path& file, const std::string& bytes) {
    if (bytes.size() > size_t(std::numeric_limits<int>::max())) throw malformed(file, "PNG too large");
    int width = 0, height = 0, channels = 0;
    stbi_us* pixels = stbi_load_16_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()),
                                               &width, &height, &channels, 3);
    if (!pixels) throw malformed(file, std::string("PNG: ") + stbi_failure_reason());
    LinearImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.rgb.resize(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = srgbDecode(float(pixels[i]) / 65535.0f);
    stbi_image_free(pixels);
    return image;
}

// Walks a Radiance file's pixel data as stb's decoder will, without decoding it: stb reads zeros past the end
// of a truncated file (an image with black rows, or a run of length 0 that never ends in Debian's stb), so a
// file is checked complete first. Returns what is wrong, or nothing; a header stb cannot read is left to it.
std::optional<std::string> hdrDataProblem(const std::string& bytes) {
    const size_t headerEnd = bytes.find("\n\n");
    if (headerEnd == std::string::npos) return std::nullopt;
    size_t pos = bytes.find('\n', headerEnd + 2);
    int height = 0, width = 0;
    if (pos == std::string::npos || std::sscanf(bytes.c_str() + headerEnd + 2, "-Y %d +X %d", &height, &width) != 2 ||
        height <= 0 || width <= 0)
        return std::nullopt;
    ++pos;
    const uint64_t pixels = uint64_t(width) * uint64_t(height), size = bytes.size();
    const auto truncated = [&](uint64_t row) {
        return "truncated: the pixel data of " + std::to_string(width) + "x" + std::to_string(height) + " ends in row " +
               std::to_string(row) + ", after " + std::to_string(size) + " bytes";
    };
    const auto flat = [&](uint64_t row) -> std::optional<std::string> {  // 4 bytes a pixel from `pos` on
        if (pos + (pixels - row * uint64_t(width)) * 4 > size) return truncated(row + (size - pos) / 4 / uint64_t(width));
        return std::nullopt;
    };
    if (width < 8 || width >= 32768) return flat(0);
    const auto byteAt = [&](size_t i) { return uint8_t(bytes[i]); };
    for (uint64_t row = 0; row < uint64_t(height); ++row) {
        if (pos + 4 > size) return truncated(row);
        if (byteAt(pos) != 2 || byteAt(pos + 1) != 2 || (byteAt(pos + 2) & 0x80)) return flat(row);  // stb reads the rest flat
        if (((byteAt(pos + 2) << 8) | byteAt(pos + 3)) != width) return std::nullopt;  // stb refuses it by name
        pos += 4;
        for (int channel = 0; channel < 4; ++channel)
            for (int filled = 0; filled < width;) {
                if (pos >= size) return truncated(row);
                int count = byteAt(pos++);
                const bool run = count > 128;
                if (run) count -= 128;
                if (count == 0 || count > width - filled)
                    return "malformed run-length data in row " + std::to_string(row);
                const size_t dataBytes = run ? 1 : size_t(count);
                if (pos + dataBytes > size) return truncated(row);
                pos += dataBytes;
                filled += count;
            }
    }
    return std::nullopt;
}

// Radiance RGBE (.hdr), linear floats as stored.
LinearImage readHdr(const std::filesystem::path& file, const std::string& bytes) {
    if (bytes.size() > size_t(std::numeric_limits<int>::max())) throw malformed(file, "HDR too large");
    if (const std::optional<std::string> problem = hdrDataProblem(bytes)) throw malformed(file, "Radiance HDR: " + *problem);
    int width = 0, height = 0, channels = 0;
    float* pixels = stbi_loadf_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &width,
                                           &height, &channels, 3);
    if (!pixels) throw malformed(file, std::string("Radiance HDR: ") + stbi_failure_reason());
    LinearImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.rgb.assign(pixels, pixels + size_t(width) * size_t(height) * 3);
    stbi_image_free(pixels);
    return image;
}

LinearImage readExr(const std::filesystem::path& file, const std::string& bytes) {
    float* rgba = nullptr;
    int width = 0, height = 0;
    const char* error = nullptr;
    if (LoadEXRFromMemory(&rgba, &width, &height, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                          &error) != TINYEXR_SUCCESS) {
        const std::string message = error ? error : "unreadable EXR";
        if (error) FreeEXRErrorMessage(error);
        throw malformed(file, "EXR: " + message);
    }
    LinearImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.rgb.resize(size_t(width) * size_t(height) * 3);
    for (size_t p = 0; p < size_t(width) * size_t(height); ++p)
        for (size_t c = 0; c < 3; ++c) image.rgb[p * 3 + c] = rgba[p * 4 + c];
    std::free(rgba);
    return image;
}

// PFM: "PF" (RGB) or "Pf" (grey), width, height, a scale whose sign gives the byte order (negative: little
// endian) and whose magnitude multiplies the samples, one whitespace byte, then rows from the bottom up.
LinearImage readPfm(const std::filesystem::path& file, const std::string& bytes) {
    std::istringstream header(bytes);
    std::string magic, widthText, heightText, scaleText;
    header >> magic >> widthText >> heightText >> scaleText;
    if (!header) throw malformed(file, "PFM header ends early (expected PF|Pf, width, height, scale)");
    const int channels = magic == "PF" ? 3 : magic == "Pf" ? 1 : 0;
    if (channels == 0) throw malformed(file, "PFM magic '" + magic + "' is neither PF nor Pf");
    auto dimension = [&](const std::string& text, const char* name) {
        size_t used = 0;
        unsigned long value = 0;
        try {
            value = std::stoul(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != text.size() || text[0] == '-' || value == 0 || value > (1u << 20))
            throw malformed(file, std::string("PFM ") + name + " '" + text + "' is not a size in 1..1048576");
        return uint32_t(value);
    };
    const uint32_t width = dimension(widthText, "width"), height = dimension(heightText, "height");
    float scale = 0;
    try {
        size_t used = 0;
        scale = std::stof(scaleText, &used);
        if (used != scaleText.size()) scale = 0;
    } catch (const std::exception&) {
        scale = 0;
    }
    if (scale == 0 || !std::isfinite(scale)) throw malformed(file, "PFM scale '" + scaleText + "' is not a non-zero number");
    const auto dataStart = size_t(header.tellg()) + 1;  // the single whitespace byte after the scale
    const size_t samples = size_t(width) * height * size_t(channels);
    if (bytes.size() < dataStart + samples * 4)
        throw malformed(file, "PFM data too short: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                                  std::to_string(samples * 4) + " bytes, the file has " +
                                  std::to_string(bytes.size() < dataStart ? 0 : bytes.size() - dataStart));
    const bool swap = (scale < 0) != (std::endian::native == std::endian::little);
    LinearImage image;
    image.width = width;
    image.height = height;
    image.rgb.resize(size_t(width) * height * 3);
    for (uint32_t fileRow = 0; fileRow < height; ++fileRow) {
        const uint32_t y = height - 1 - fileRow;  // the file's first row is the bottom one
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                const size_t sample = (size_t(fileRow) * width + x) * size_t(channels) + size_t(channels == 3 ? c : 0);
                uint32_t word;
                std::memcpy(&word, bytes.data() + dataStart + sample * 4, 4);
                if (swap) word = (word >> 24) | ((word >> 8) & 0xff00u) | ((word << 8) & 0xff0000u) | (word << 24);
                image.rgb[(size_t(y) * width + x) * 3 + size_t(c)] = std::bit_cast<float>(word) * std::abs(scale);
            }
    }
    return image;
}

}  // namespace

void writePngBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const uint8_t* rgba) {
    checkSize(file, width, height, rgba);
    // Copied top row first: PNG rows run down the image. (stb's flip switch is global state; a copy is not.)
    const size_t rowBytes = size_t(width) * 4;
    std::vector<uint8_t> topDown(rowBytes * height);
    for (uint32_t y = 0; y < height; ++y)
        std::memcpy(topDown.data() + size_t(height - 1 - y) * rowBytes, rgba + size_t(y) * rowBytes, rowBytes);
    std::string png;
    if (!stbi_write_png_to_func(appendBytes, &png, int(width), int(height), 4, topDown.data(), int(rowBytes)))
        throw std::runtime_error(file.string() + ": cannot encode the PNG");
    writeFileAtomically(file, png, "the image");
}

void writePfmBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba) {
    checkSize(file, width, height, rgba);
    // "PF": colour; a negative scale says little-endian.
    std::string pfm = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    std::vector<float> row(size_t(width) * 3);
    for (uint32_t y = 0; y < height; ++y) {
        const float* src = rgba + size_t(y) * width * 4;
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) row[size_t(x) * 3 + size_t(c)] = src[size_t(x) * 4 + size_t(c)];
        pfm.append(reinterpret_cast<const char*>(row.data()), row.size() * sizeof(float));
    }
    writeFileAtomically(file, pfm, "the image");
}

void writeExrBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba) {
    checkSize(file, width, height, rgba);
    writeExrChannelsBottomUp(file, width, height,
                             {{"R", rgba, 4}, {"G", rgba + 1, 4}, {"B", rgba + 2, 4}, {"A", rgba + 3, 4}});
}

void writeExrChannelsBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height,
                              std::vector<ExrChannel> channels) {
    if (channels.empty()) throw std::runtime_error(file.string() + ": an EXR image needs a channel");
    for (const ExrChannel& c : channels) checkSize(file, width, height, c.values);
    std::sort(channels.begin(), channels.end(), [](const ExrChannel& a, const ExrChannel& b) { return a.name < b.name; });
    const size_t pixels = size_t(width) * height;
    // Planar, rows top first, as tinyexr takes them.
    std::vector<std::vector<float>> planes(channels.size(), std::vector<float>(pixels));
    std::vector<unsigned char*> planePointers;
    std::vector<EXRChannelInfo> infos(channels.size());
    std::vector<int> pixelTypes(channels.size(), TINYEXR_PIXELTYPE_FLOAT), requestedTypes(channels.size());
    for (size_t c = 0; c < channels.size(); ++c) {
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x)
                planes[c][size_t(y) * width + x] = channels[c].values[(size_t(height - 1 - y) * width + x) * channels[c].stride];
        planePointers.push_back(reinterpret_cast<unsigned char*>(planes[c].data()));
        std::snprintf(infos[c].name, sizeof infos[c].name, "%s", channels[c].name.c_str());
        requestedTypes[c] = channels[c].half ? TINYEXR_PIXELTYPE_HALF : TINYEXR_PIXELTYPE_FLOAT;
    }
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = int(channels.size());
    header.channels = infos.data();
    header.pixel_types = pixelTypes.data();
    header.requested_pixel_types = requestedTypes.data();
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = int(channels.size());
    image.images = planePointers.data();
    image.width = int(width);
    image.height = int(height);
    const char* error = nullptr;
    unsigned char* exr = nullptr;
    const size_t exrBytes = SaveEXRImageToMemory(&image, &header, &exr, &error);
    if (exrBytes == 0) {
        const std::string message = error ? error : "tinyexr could not encode it";
        if (error) FreeEXRErrorMessage(error);
        std::free(exr);
        throw std::runtime_error(file.string() + ": cannot encode the EXR image: " + message);
    }
    const std::string bytes(reinterpret_cast<const char*>(exr), exrBytes);
    std::free(exr);
    writeFileAtomically(file, bytes, "the image");
}

std::vector<uint8_t> encodeSrgb8(uint32_t width, uint32_t height, const float* rgba) {
    std::vector<uint8_t> bytes(size_t(width) * height * 4);
    for (size_t i = 0; i < bytes.size(); ++i) {
        const float value = std::clamp(rgba[i], 0.0f, 1.0f);  // NaN stays NaN through clamp: caught below
        const float encoded = i % 4 == 3 ? value : srgbEncode(value);
        bytes[i] = std::isnan(encoded) ? 0 : uint8_t(std::lround(encoded * 255.0f));
    }
    return bytes;
}

void writePngFromLinearBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height, const float* rgba) {
    checkSize(file, width, height, rgba);
    writePngBottomUp(file, width, height, encodeSrgb8(width, height, rgba).data());
}

void writeJpegFromLinearBottomUp(const std::filesystem::path& file, uint32_t width, uint32_t height,
                                 const float* rgba) {
    checkSize(file, width, height, rgba);
    const std::vector<uint8_t> bytes = encodeSrgb8(width, height, rgba);
    // JPEG rows run top to bottom and carry no alpha.
    std::vector<uint8_t> rgb(size_t(width) * height * 3);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(size_t(y) * width + x) * 3 + size_t(c)] = bytes[(size_t(height - 1 - y) * width + x) * 4 + size_t(c)];
    std::string jpeg;
    if (!stbi_write_jpg_to_func(appendBytes, &jpeg, int(width), int(height), 3, rgb.data(), 95))
        throw std::runtime_error(file.string() + ": cannot encode the JPEG");
    writeFileAtomically(file, jpeg, "the image");
}

LinearImage readLinearImage(const std::filesystem::path& file) {
    std::string bytes, error;
    if (!readRegularFile(file, kMaxImageFileBytes, false, bytes, error))
        throw std::runtime_error(file.string() + ": cannot open the image (" + error + ")");
    static const std::string pngMagic = "\x89PNG\r\n\x1a\n", exrMagic = "\x76\x2f\x31\x01";
    if (bytes.compare(0, pngMagic.size(), pngMagic) == 0) return readPng(file, bytes);
    if (bytes.compare(0, exrMagic.size(), exrMagic) == 0) return readExr(file, bytes);
    if (bytes.compare(0, 10, "#?RADIANCE") == 0 || bytes.compare(0, 6, "#?RGBE") == 0) return readHdr(file, bytes);
    if (bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f') && std::isspace(uint8_t(bytes[2])))
        return readPfm(file, bytes);
    throw std::runtime_error(file.string() + ": not a PNG, PFM, EXR or Radiance HDR image (unrecognised first bytes)");
}

}  // namespace ripple::apps
