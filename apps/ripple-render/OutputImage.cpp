// Output format, writability check and writer of ripple-render (see OutputImage.h). PNG and PFM go through
// the project's image writer; JPEG through stb_image_write, which that writer already uses for PNG.
#include "apps/ripple-render/OutputImage.h"

#include "apps/common/ImageIO.h"
#include "apps/common/ImageMetricsDetail.h"

#include <stb_image_write.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

OutputFormat outputFormatOf(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".png") return OutputFormat::Png;
    if (extension == ".jpg" || extension == ".jpeg") return OutputFormat::Jpeg;
    if (extension == ".pfm") return OutputFormat::Pfm;
    throw std::runtime_error("-o " + file.string() + ": unsupported image format '" + file.extension().string() +
                             "' (supported: .png, .jpg, .jpeg, .pfm)");
}

void checkOutputWritable(const std::filesystem::path& file) {
    // Opening is the only test that sees what writing will see (permissions, read-only mounts, a folder
    // in the way); access() answers for the real user and ignores read-only file systems' subtleties.
    const bool existed = std::filesystem::exists(file);
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int error = errno;
        throw std::runtime_error("-o " + file.string() + ": cannot write the image there: " + std::strerror(error));
    }
    ::close(fd);
    if (!existed) ::unlink(file.c_str());
}

void writeOutputImage(const std::filesystem::path& file, OutputFormat format, uint32_t width, uint32_t height,
                      const float* rgba) {
    if (format == OutputFormat::Pfm) return writePfmBottomUp(file, width, height, rgba);
    if (format == OutputFormat::Png) return writePngFromLinearBottomUp(file, width, height, rgba);
    // JPEG rows run top to bottom and carry no alpha.
    std::vector<uint8_t> rgb(size_t(width) * height * 3);
    for (uint32_t y = 0; y < height; ++y) {
        const float* row = rgba + size_t(height - 1 - y) * width * 4;
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float encoded = detail::srgbEncode(std::clamp(row[size_t(x) * 4 + size_t(c)], 0.0f, 1.0f));
                rgb[(size_t(y) * width + x) * 3 + size_t(c)] = std::isnan(encoded) ? 0 : uint8_t(std::lround(encoded * 255.0f));
            }
    }
    if (!stbi_write_jpg(file.c_str(), int(width), int(height), 3, rgb.data(), 95))
        throw std::runtime_error(file.string() + ": cannot write the JPEG");
}

}  // namespace ripple::apps
