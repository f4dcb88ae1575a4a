// Output format, writability check and writer of the apps' image files (see OutputImage.h); the pixels go through
// the project's one image writer (io/image/ImageIO).
#include "io/image/OutputImage.h"

#include "io/FileWrite.h"
#include "io/image/ImageIO.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

OutputFormat outputFormatOf(const std::filesystem::path& file, const std::string& option) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".png") return OutputFormat::Png;
    if (extension == ".jpg" || extension == ".jpeg") return OutputFormat::Jpeg;
    if (extension == ".pfm") return OutputFormat::Pfm;
    if (extension == ".exr") return OutputFormat::Exr;
    throw std::runtime_error(option + " " + file.string() + ": unsupported image format '" + file.extension().string() +
                             "' (supported: .png, .jpg, .jpeg, .pfm, .exr)");
}

void checkOutputWritable(const std::filesystem::path& file, const std::string& option) {
    try {
        checkWritable(file, "the image");
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(option + " " + e.what());
    }
}

void writeOutputImage(const std::filesystem::path& file, OutputFormat format, uint32_t width, uint32_t height,
                      const float* rgba) {
    if (format == OutputFormat::Pfm) return writePfmBottomUp(file, width, height, rgba);
    if (format == OutputFormat::Exr) return writeExrBottomUp(file, width, height, rgba);
    if (format == OutputFormat::Png) return writePngFromLinearBottomUp(file, width, height, rgba);
    writeJpegFromLinearBottomUp(file, width, height, rgba);
}

}  // namespace ripple::apps
