// Small glTF files written by the tests themselves: a temp folder, GLB and .gltf writers, and a one-triangle
// scene whose JSON and binary the malformed-file tests corrupt one element at a time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::test {

// A fresh folder under the system temp dir, removed with everything in it when the object goes.
class TempFolder {
public:
    TempFolder();
    ~TempFolder();
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

// glTF JSON plus the bytes of its binary buffer (buffer 0).
struct GltfSource {
    std::string json;
    std::vector<uint8_t> bin;

    // Replaces the first occurrence of `from` in the JSON; fails the test when it is absent.
    GltfSource& replace(const std::string& from, const std::string& to);
    // Makes buffer 0 the file `uri` names (as written in the JSON string, so no quotes or backslashes);
    // the caller writes `bin` there.
    GltfSource& externalBuffer(const std::string& uri);
    // Overwrites bin bytes at `offset` with the raw bytes of `value`.
    template <typename T>
    GltfSource& poke(size_t offset, const T& value) {
        const auto* bytes = reinterpret_cast<const uint8_t*>(&value);
        for (size_t i = 0; i < sizeof(T); ++i) bin.at(offset + i) = bytes[i];
        return *this;
    }
};

// One triangle (positions (0,0,0), (1,0,0), (0,1,0); uint32 indices 0 1 2) drawn by node 0 of scene 0.
// Bin: 36 bytes of positions (buffer view 0, accessor 0), then 12 bytes of indices (view 1, accessor 1).
GltfSource triangleSource();

// .glb with the JSON chunk padded with spaces and the BIN chunk (when bin is not empty) padded with zeros.
std::vector<uint8_t> glbBytes(const GltfSource& source);
std::filesystem::path writeGlb(const std::filesystem::path& file, const GltfSource& source);
std::filesystem::path writeBytes(const std::filesystem::path& file, const std::vector<uint8_t>& bytes);
std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text);

// An RGBA8 image encoded as PNG (stb_image_write), rows top first.
std::vector<uint8_t> pngBytes(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

}  // namespace ripple::test
