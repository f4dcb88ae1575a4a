// glTF -> one world-space TriangleMesh, with tinygltf doing the parsing and this file checking every range it
// reads, so a truncated or inconsistent file ends in an error that names the accessor rather than a crash.
#include "apps/ripple-bench/GltfMeshes.h"

// Debian ships tinygltf as a compiled library; where CMake finds none, this file compiles it in, without
// image codecs (geometry only) so that stb is not needed. nlohmann/json.hpp still is.
#ifdef RIPPLE_BENCH_TINYGLTF_IMPLEMENTATION
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cstring>
#include <limits>
#include <stdexcept>

namespace ripple::bench {

namespace {

// Geometry only: images are neither decoded nor checked (bunny and Sponza carry none, others need not).
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
    return true;
}

class Flattener {
public:
    Flattener(const tinygltf::Model& model, std::string file) : model_(model), file_(std::move(file)) {}

    void node(int index, const glm::dmat4& parent, int depth) {
        // glTF forbids cycles; the depth cap turns a malformed file into an error instead of a stack overflow.
        if (index < 0 || size_t(index) >= model_.nodes.size() || depth > 1024)
            fail("node " + std::to_string(index) + " is out of range or the hierarchy is cyclic");
        const tinygltf::Node& n = model_.nodes[size_t(index)];
        const glm::dmat4 world = parent * localTransform(n);
        if (n.mesh >= 0) mesh(n.mesh, world);
        for (int child : n.children) node(child, world, depth + 1);
    }

    void mesh(int index, const glm::dmat4& world) {
        if (size_t(index) >= model_.meshes.size()) fail("mesh " + std::to_string(index) + " is out of range");
        for (const tinygltf::Primitive& p : model_.meshes[size_t(index)].primitives) {
            if (p.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points, lines and strips are not benchmarked
            primitive(p, world);
        }
    }

    core::TriangleMesh take() { return std::move(out_); }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(file_ + ": " + what);
    }

    static glm::dmat4 localTransform(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());  // column-major, as glm
        glm::dmat4 m(1.0);
        if (n.translation.size() == 3) m = glm::translate(m, glm::make_vec3(n.translation.data()));
        if (n.rotation.size() == 4)  // glTF stores x, y, z, w
            m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
        if (n.scale.size() == 3) m = glm::scale(m, glm::make_vec3(n.scale.data()));
        return m;
    }

    // Start and stride of an accessor's elements, after checking that all `count` of them lie in its buffer.
    const unsigned char* elements(int accessorIndex, size_t elementBytes, size_t& stride) const {
        const std::string name = "accessor " + std::to_string(accessorIndex);
        if (accessorIndex < 0 || size_t(accessorIndex) >= model_.accessors.size()) fail(name + " does not exist");
        const tinygltf::Accessor& a = model_.accessors[size_t(accessorIndex)];
        if (a.sparse.isSparse) fail(name + " is sparse (not supported)");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
            fail(name + " has no valid buffer view");
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            fail(name + ": buffer view " + std::to_string(a.bufferView) + " has no valid buffer");
        const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
        stride = view.byteStride ? view.byteStride : elementBytes;
        if (stride < elementBytes) fail(name + ": byte stride " + std::to_string(stride) + " is below element size");
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
            fail(name + ": buffer view " + std::to_string(a.bufferView) + " runs past its buffer");
        const size_t needed = a.count == 0 ? 0 : a.byteOffset + (a.count - 1) * stride + elementBytes;
        if (a.count > 0 && (a.count - 1 > (std::numeric_limits<size_t>::max() - a.byteOffset) / stride ||
                            needed > view.byteLength))
            fail(name + ": " + std::to_string(a.count) + " elements run past buffer view " +
                 std::to_string(a.bufferView));
        return data.data() + view.byteOffset + a.byteOffset;
    }

    void primitive(const tinygltf::Primitive& p, const glm::dmat4& world) {
        const auto position = p.attributes.find("POSITION");
        if (position == p.attributes.end()) fail("a TRIANGLES primitive has no POSITION attribute");
        const int posIndex = position->second;
        const std::string name = "accessor " + std::to_string(posIndex) + " (POSITION)";
        if (posIndex < 0 || size_t(posIndex) >= model_.accessors.size()) fail(name + " does not exist");
        const tinygltf::Accessor& pa = model_.accessors[size_t(posIndex)];
        if (pa.type != TINYGLTF_TYPE_VEC3 || pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pa.normalized)
            fail(name + " is not float VEC3");
        size_t stride = 0;
        const unsigned char* src = elements(posIndex, sizeof(float) * 3, stride);
        const size_t base = out_.positions.size();
        if (pa.count > size_t(std::numeric_limits<uint32_t>::max()) - base)
            fail("more than 2^32 vertices in total");
        for (size_t i = 0; i < pa.count; ++i) {
            float xyz[3];
            std::memcpy(xyz, src + i * stride, sizeof xyz);  // glTF does not promise 4-byte alignment
            out_.positions.emplace_back(world * glm::dvec4(xyz[0], xyz[1], xyz[2], 1.0));
        }
        if (p.indices < 0) {
            if (pa.count % 3) fail(name + ": vertex count is not a multiple of 3");
            for (size_t i = 0; i < pa.count; i += 3)
                out_.indices.emplace_back(uint32_t(base + i), uint32_t(base + i + 1), uint32_t(base + i + 2));
            return;
        }
        indices(p.indices, uint32_t(base), pa.count);
    }

    void indices(int accessorIndex, uint32_t base, size_t vertexCount) {
        const std::string name = "accessor " + std::to_string(accessorIndex) + " (indices)";
        if (accessorIndex < 0 || size_t(accessorIndex) >= model_.accessors.size()) fail(name + " does not exist");
        const tinygltf::Accessor& a = model_.accessors[size_t(accessorIndex)];
        if (a.type != TINYGLTF_TYPE_SCALAR) fail(name + " is not SCALAR");
        size_t bytes = 0;
        switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: bytes = 1; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: bytes = 2; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: bytes = 4; break;
            default: fail(name + " is not uint8, uint16 or uint32");
        }
        size_t stride = 0;
        const unsigned char* src = elements(accessorIndex, bytes, stride);
        const size_t count = a.count;
        if (count % 3) fail(name + ": index count " + std::to_string(count) + " is not a multiple of 3");
        auto read = [&](size_t i) -> uint32_t {
            const unsigned char* at = src + i * stride;
            if (bytes == 1) return *at;
            if (bytes == 2) { uint16_t v; std::memcpy(&v, at, 2); return v; }
            uint32_t v; std::memcpy(&v, at, 4); return v;
        };
        for (size_t i = 0; i < count; i += 3) {
            glm::uvec3 tri(read(i), read(i + 1), read(i + 2));
            for (int k = 0; k < 3; ++k)
                if (tri[k] >= vertexCount)
                    fail(name + ": index " + std::to_string(tri[k]) + " at element " + std::to_string(i + size_t(k)) +
                         " is not below the vertex count " + std::to_string(vertexCount));
            out_.indices.push_back(tri + glm::uvec3(base));
        }
    }

    const tinygltf::Model& model_;
    std::string file_;
    core::TriangleMesh out_;
};

}  // namespace

core::TriangleMesh loadGltfTriangles(const std::filesystem::path& file) {
    if (!std::filesystem::is_regular_file(file)) throw std::runtime_error(file.string() + ": no such file");
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skipImage, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    const bool binary = file.extension() == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, file.string())
                           : loader.LoadASCIIFromFile(&model, &error, &warning, file.string());
    if (!ok) throw std::runtime_error(file.string() + ": " + (error.empty() ? "tinygltf could not read it" : error));

    Flattener flat(model, file.string());
    if (!model.scenes.empty()) {
        const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (size_t(sceneIndex) >= model.scenes.size())
            throw std::runtime_error(file.string() + ": default scene " + std::to_string(sceneIndex) + " does not exist");
        for (int root : model.scenes[size_t(sceneIndex)].nodes) flat.node(root, glm::dmat4(1.0), 0);
    } else {
        // No scene: glTF leaves the choice to the application; take every node that is nobody's child.
        std::vector<bool> isChild(model.nodes.size(), false);
        for (const tinygltf::Node& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) flat.node(int(i), glm::dmat4(1.0), 0);
    }
    core::TriangleMesh mesh = flat.take();
    if (mesh.indices.empty()) throw std::runtime_error(file.string() + ": no TRIANGLES primitives found");
    return mesh;
}

}  // namespace ripple::bench
