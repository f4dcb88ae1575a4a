// The apps' output image files (ripple-render -o, ripple-view --screenshot): the format from the extension
// (PNG, JPEG, PFM or EXR; any other is refused with the list), a check that the file can be written before
// anything renders, and the writer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace ripple::apps {

enum class OutputFormat { Png, Jpeg, Pfm, Exr };

// Throws std::runtime_error naming the option, the file and the supported extensions when there is none of them.
OutputFormat outputFormatOf(const std::filesystem::path& file, const std::string& option = "-o");

// Throws std::runtime_error with the operating system's reason when `file` cannot be created or
// replaced (missing or read-only folder, a folder of that name...). Touches no file of that name.
void checkOutputWritable(const std::filesystem::path& file, const std::string& option = "-o");

// Linear RGBA pixels, bottom row first: PNG and JPEG as 8-bit sRGB (JPEG without alpha), PFM (RGB) and EXR
// (RGBA) as 32-bit floats.
void writeOutputImage(const std::filesystem::path& file, OutputFormat format, uint32_t width, uint32_t height,
                      const float* rgba);

}  // namespace ripple::apps
