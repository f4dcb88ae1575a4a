// Writers for the tests' own glTF files; the GLB layout (12-byte header, 8-byte chunk headers, 4-byte
// padding) follows the glTF 2.0 specification.
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image_write.h>

#include <atomic>
#include <cstring>
#include <fstream>
#include <random>

namespace ripple::test {

TempFolder::TempFolder() {
    static std::atomic<int> counter{0};
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("ripple-app-tests-" + std::to_string(random()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
}

TempFolder::~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

GltfSource& GltfSource::replace(const std::string& from, const std::string& to) {
    const size_t at = json.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, "test JSON lacks '" << from << "'");
    json.replace(at, from.size(), to);
    return *this;
}

GltfSource& GltfSource::externalBuffer(const std::string& uri) {
    return replace(R"("buffers":[{"byteLength":48)", R"("buffers":[{"byteLength":48,"uri":")" + uri + "\"");
}

GltfSource triangleSource() {
    GltfSource s;
    s.json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"buffers":[{"byteLength":48}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}]})";
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t indices[3] = {0, 1, 2};
    s.bin.resize(48);
    std::memcpy(s.bin.data(), positions, 36);
    std::memcpy(s.bin.data() + 36, indices, 12);
    return s;
}

std::vector<uint8_t> glbBytes(const GltfSource& source) {
    std::string json = source.json;
    while (json.size() % 4) json += ' ';
    std::vector<uint8_t> bin = source.bin;
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> out;
    const auto put32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    const uint32_t total = uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size()));
    put32(0x46546C67);  // "glTF"
    put32(2);
    put32(total);
    put32(uint32_t(json.size()));
    put32(0x4E4F534A);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    if (!bin.empty()) {
        put32(uint32_t(bin.size()));
        put32(0x004E4942);  // "BIN\0"
        out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
}

std::filesystem::path writeBytes(const std::filesystem::path& file, const std::vector<uint8_t>& bytes) {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    REQUIRE_MESSAGE(out.good(), "cannot write " << file);
    return file;
}

std::filesystem::path writeGlb(const std::filesystem::path& file, const GltfSource& source) {
    return writeBytes(file, glbBytes(source));
}

std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text) {
    return writeBytes(file, std::vector<uint8_t>(text.begin(), text.end()));
}

std::vector<uint8_t> pngBytes(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
    std::vector<uint8_t> out;
    const auto append = [](void* context, void* data, int size) {
        auto* target = static_cast<std::vector<uint8_t>*>(context);
        target->insert(target->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    REQUIRE(stbi_write_png_to_func(append, &out, int(width), int(height), 4, rgba.data(), int(width) * 4));
    return out;
}

}  // namespace ripple::test
