// Checked accessor reads: ranges are computed in size_t with overflow checks before any byte is touched, and
// reads go through memcpy because glTF promises no alignment beyond the component size.
#include "io/gltf/GltfAccessors.h"

#include "io/gltf/GltfScene.h"

#include <tiny_gltf.h>

#include <cstring>
#include <limits>

namespace ripple::apps::gltf {

namespace {

// An accessor with no buffer view is all zeros (plus sparse values), so nothing bounds its count but this.
constexpr size_t kMaxElements = size_t(1) << 28;

size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

int componentsOf(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        default: return 0;  // matrices are no vertex attribute this importer reads
    }
}

const char* componentName(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "int8";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "uint8";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "int16";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "uint16";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "uint32";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float32";
        default: return "an unknown component type";
    }
}

uint32_t readUnsigned(const unsigned char* at, size_t bytes) {
    if (bytes == 1) return *at;
    if (bytes == 2) {
        uint16_t v;
        std::memcpy(&v, at, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, at, 4);
    return v;
}

float readComponent(const unsigned char* at, int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, at, 4);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return float(*at) / 255.0f;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return float(readUnsigned(at, 2)) / 65535.0f;
        default: return 0.0f;  // excluded by the caller's component check
    }
}

uint32_t maskOf(int componentType, bool normalized) {
    if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return normalized ? 0u : uint32_t(kFloat);
    if (!normalized) return 0;
    if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return kUByteNorm;
    if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return kUShortNorm;
    return 0;
}

}  // namespace

void AccessorReader::fail(const std::string& what) const {
    throw GltfError(context_ + what);
}

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& name) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(name + " does not exist (the file has " + std::to_string(model_.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    if (a.count > kMaxElements)
        fail(name + ": count " + std::to_string(a.count) + " is absurd (more than " +
             std::to_string(kMaxElements) + ")");
    return a;
}

AccessorReader::Span AccessorReader::locate(const std::string& name, int bufferView, size_t byteOffset,
                                            size_t count, size_t elementBytes, bool strided) const {
    if (bufferView < 0) return {};
    if (size_t(bufferView) >= model_.bufferViews.size())
        fail(name + ": buffer view " + std::to_string(bufferView) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(bufferView)];
    const std::string viewName = "buffer view " + std::to_string(bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        fail(name + ": " + viewName + " names buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        fail(name + ": " + viewName + " (offset " + std::to_string(view.byteOffset) + ", length " +
             std::to_string(view.byteLength) + ") runs past buffer " + std::to_string(view.buffer) + " (" +
             std::to_string(data.size()) + " bytes)");
    const size_t stride = strided && view.byteStride ? view.byteStride : elementBytes;
    if (stride < elementBytes)
        fail(name + ": byte stride " + std::to_string(stride) + " of " + viewName + " is below the element size " +
             std::to_string(elementBytes));
    if (count > 0) {
        // offset + (count - 1) * stride + elementBytes <= byteLength, without overflow.
        const size_t limit = view.byteLength;
        const bool fits = byteOffset <= limit && elementBytes <= limit - byteOffset &&
                          count - 1 <= (limit - byteOffset - elementBytes) / stride;
        if (!fits)
            fail(name + ": " + std::to_string(count) + " elements of " + std::to_string(elementBytes) +
                 " bytes at offset " + std::to_string(byteOffset) + " run past " + viewName + " (" +
                 std::to_string(limit) + " bytes)");
    }
    return {data.data() + view.byteOffset + byteOffset, stride};
}

std::vector<glm::vec4> AccessorReader::readFloats(int index, const char* role, int minComponents,
                                                  int maxComponents, uint32_t allowed) const {
    const std::string name = "accessor " + std::to_string(index) + " (" + role + ")";
    const tinygltf::Accessor& a = accessor(index, name);
    const int components = componentsOf(a.type);
    if (components < minComponents || components > maxComponents)
        fail(name + " has " + (components ? std::to_string(components) + " components" : "a matrix type") +
             ", expected " + std::to_string(minComponents) +
             (maxComponents > minComponents ? " to " + std::to_string(maxComponents) : std::string()));
    if (!(maskOf(a.componentType, a.normalized) & allowed))
        fail(name + " has component type " + componentName(a.componentType) +
             (a.normalized ? " (normalized)" : "") + ", which glTF does not allow here");
    const size_t bytes = componentBytes(a.componentType);
    const Span span = locate(name, a.bufferView, a.byteOffset, a.count, bytes * size_t(components), true);

    std::vector<glm::vec4> out(a.count, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (span.data)
        for (size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < components; ++c)
                out[i][c] = readComponent(span.data + i * span.stride + size_t(c) * bytes, a.componentType);
    if (a.sparse.isSparse) applySparse(index, name, components, out);
    return out;
}

void AccessorReader::applySparse(int index, const std::string& name, int components,
                                 std::vector<glm::vec4>& out) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    const auto& sparse = a.sparse;
    if (sparse.count < 0 || size_t(sparse.count) > out.size())
        fail(name + ": sparse count " + std::to_string(sparse.count) + " exceeds the element count " +
             std::to_string(out.size()));
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
        fail(name + ": negative sparse byte offset");
    const size_t n = size_t(sparse.count);
    const size_t indexBytes = componentBytes(sparse.indices.componentType);
    if (indexBytes == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail(name + ": sparse indices are not uint8, uint16 or uint32");
    const size_t bytes = componentBytes(a.componentType);
    const std::string indicesName = name + " sparse indices";
    const std::string valuesName = name + " sparse values";
    if (sparse.indices.bufferView < 0) fail(indicesName + " have no buffer view");
    if (sparse.values.bufferView < 0) fail(valuesName + " have no buffer view");
    const Span indexSpan =
        locate(indicesName, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), n, indexBytes, false);
    const Span valueSpan = locate(valuesName, sparse.values.bufferView, size_t(sparse.values.byteOffset), n,
                                  bytes * size_t(components), false);
    for (size_t k = 0; k < n; ++k) {
        const uint32_t target = readUnsigned(indexSpan.data + k * indexSpan.stride, indexBytes);
        if (target >= out.size())
            fail(indicesName + ": index " + std::to_string(target) + " out of range for " +
                 std::to_string(out.size()) + " elements");
        for (int c = 0; c < components; ++c)
            out[target][c] = readComponent(valueSpan.data + k * valueSpan.stride + size_t(c) * bytes, a.componentType);
    }
}

std::vector<uint32_t> AccessorReader::readIndices(int index) const {
    const std::string name = "accessor " + std::to_string(index) + " (indices)";
    const tinygltf::Accessor& a = accessor(index, name);
    if (a.type != TINYGLTF_TYPE_SCALAR) fail(name + " is not SCALAR");
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(name + " has component type " + componentName(a.componentType) + ", expected uint8, uint16 or uint32");
    if (a.sparse.isSparse) fail(name + " is sparse, which glTF does not allow for indices");
    const size_t bytes = componentBytes(a.componentType);
    const Span span = locate(name, a.bufferView, a.byteOffset, a.count, bytes, true);
    std::vector<uint32_t> out(a.count, 0);
    if (span.data)
        for (size_t i = 0; i < a.count; ++i) out[i] = readUnsigned(span.data + i * span.stride, bytes);
    return out;
}

}  // namespace ripple::apps::gltf
