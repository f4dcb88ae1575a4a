// Generates the displaced cube-sphere used by the "builtin" and "procedural" benchmark scenes.
#include "bench/ripple-bench/ProceduralMeshes.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

namespace ripple::bench {

namespace {

// Radial displacement: large, medium and fine bumps; amplitudes keep the surface well away from the centre.
float displacement(const glm::vec3& d) {
    return 1.0f + 0.10f * std::sin(5.0f * d.x + 1.3f) * std::sin(6.0f * d.y + 0.7f) * std::sin(4.0f * d.z + 2.1f) +
           0.04f * std::sin(17.0f * d.x + 13.0f * d.y) * std::cos(11.0f * d.z) +
           0.01f * std::sin(61.0f * d.y + 47.0f * d.z);
}

}  // namespace

core::TriangleMesh displacedCubeSphere(uint32_t n) {
    core::TriangleMesh mesh;
    const uint32_t side = n + 1;
    mesh.positions.reserve(size_t(6) * side * side);
    mesh.indices.reserve(size_t(12) * n * n);
    for (uint32_t face = 0; face < 6; ++face) {
        const int axis = int(face / 2);
        const float sign = face % 2 ? -1.0f : 1.0f;
        const uint32_t base = uint32_t(mesh.positions.size());
        for (uint32_t j = 0; j <= n; ++j) {
            for (uint32_t i = 0; i <= n; ++i) {
                // The tangent warp evens out triangle sizes between face centres and corners.
                const float a = std::tan(glm::quarter_pi<float>() * (-1.0f + 2.0f * float(i) / float(n)));
                const float b = std::tan(glm::quarter_pi<float>() * (-1.0f + 2.0f * float(j) / float(n)));
                glm::vec3 p;
                p[axis] = sign;
                p[(axis + 1) % 3] = a;
                p[(axis + 2) % 3] = b;
                const glm::vec3 d = glm::normalize(p);
                mesh.positions.push_back(d * displacement(d));
            }
        }
        for (uint32_t j = 0; j < n; ++j) {
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t v00 = base + j * side + i;
                const uint32_t v10 = v00 + 1;
                const uint32_t v01 = v00 + side;
                const uint32_t v11 = v01 + 1;
                mesh.indices.emplace_back(v00, v10, v11);
                mesh.indices.emplace_back(v00, v11, v01);
            }
        }
    }
    return mesh;
}

}  // namespace ripple::bench
