// What a scene is made of, as the host sees it: meshes, sphere sets and instances of them. core::Scene
// validates this, builds the BVHs and uploads the flat GPU scene of shaders/shared/scene.h.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace ripple::core {

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;  // empty: consecutive position triples form the triangles
};

struct SphereSet {
    std::vector<glm::vec3> centers;
    std::vector<float> radii;         // one per center, or a single radius for all
};

enum class GeometryKind : uint32_t { Triangles = 0, Spheres = 1 };

struct GeometryRef {
    GeometryKind kind = GeometryKind::Triangles;
    uint32_t index = 0;               // into SceneDescription::meshes or ::sphereSets
};

struct InstanceDescription {
    GeometryRef geometry;
    glm::mat4 transform{1.0f};        // object to world; must be affine and invertible
};

struct SceneDescription {
    std::vector<TriangleMesh> meshes;
    std::vector<SphereSet> sphereSets;
    std::vector<InstanceDescription> instances;
};

}  // namespace ripple::core
