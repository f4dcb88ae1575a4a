// Checked reading of glTF accessors: every byte range is proven to lie inside its buffer before it is read,
// so a hostile file ends in a GltfError naming the accessor, never in a read past the end.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Accessor;
}

namespace ripple::apps::gltf {

// Which component types an attribute accessor may have, as glTF allows them per attribute.
enum ComponentMask : uint32_t {
    kFloat = 1u << 0,
    kUByteNorm = 1u << 1,    // normalized unsigned byte -> [0, 1]
    kUShortNorm = 1u << 2,   // normalized unsigned short -> [0, 1]
};

class AccessorReader {
public:
    // `context` prefixes every message (the file, the mesh and primitive being read).
    AccessorReader(const tinygltf::Model& model, std::string context)
        : model_(model), context_(std::move(context)) {}

    // Accessor `index` as floats, normalized integers mapped to [0, 1]. It must have between minComponents
    // and maxComponents components per element; components it lacks read as (0, 0, 0, 1).
    // `role` names it in messages ("POSITION").
    std::vector<glm::vec4> readFloats(int index, const char* role, int minComponents, int maxComponents,
                                      uint32_t allowed) const;

    // Unsigned 8/16/32-bit scalar indices.
    std::vector<uint32_t> readIndices(int index) const;

private:
    // `count` elements of `elementBytes` each, `stride` apart, all proven inside the buffer.
    struct Span {
        const unsigned char* data = nullptr;  // null: no buffer view, the elements are zero
        size_t stride = 0;
    };
    Span locate(const std::string& name, int bufferView, size_t byteOffset, size_t count, size_t elementBytes,
                bool strided) const;
    void applySparse(int index, const std::string& name, int components, std::vector<glm::vec4>& out) const;
    const tinygltf::Accessor& accessor(int index, const std::string& name) const;
    [[noreturn]] void fail(const std::string& what) const;

    const tinygltf::Model& model_;
    std::string context_;
};

}  // namespace ripple::apps::gltf
