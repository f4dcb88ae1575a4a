// glTF -> one world-space TriangleMesh: the importer shares geometry between instances, the benchmark wants
// every drawn triangle in one mesh, so each instance's copy is transformed and appended here.
#include "bench/ripple-bench/GltfMeshes.h"

#include "io/gltf/GltfScene.h"

#include <limits>
#include <stdexcept>

namespace ripple::bench {

core::TriangleMesh loadGltfTriangles(const std::filesystem::path& file) {
    const apps::GltfScene scene = apps::loadGltf(file, {.decodeImages = false});
    core::TriangleMesh out;
    for (const apps::GltfMeshInstance& instance : scene.instances)
        for (const apps::GltfPrimitive& primitive : scene.meshes[instance.mesh].primitives) {
            const apps::GltfGeometry& g = scene.geometries[primitive.geometry];
            const size_t base = out.positions.size();
            if (g.positions.size() > size_t(std::numeric_limits<uint32_t>::max()) - base)
                throw std::runtime_error(file.string() + ": more than 2^32 vertices once instances are flattened");
            for (const glm::vec3& p : g.positions) out.positions.emplace_back(instance.transform * glm::vec4(p, 1.0f));
            for (const glm::uvec3& t : g.indices) out.indices.push_back(t + glm::uvec3(uint32_t(base)));
        }
    if (out.indices.empty()) throw std::runtime_error(file.string() + ": no TRIANGLES primitives found");
    return out;
}

}  // namespace ripple::bench
