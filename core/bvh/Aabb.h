// Axis-aligned boxes for BVH construction (host side only).
#pragma once

#include <glm/glm.hpp>

#include <limits>

namespace ripple::bvh {

struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};

    void extend(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void extend(const Aabb& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    float halfArea() const {
        if (empty()) return 0.0f;
        const glm::vec3 d = hi - lo;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
};

}  // namespace ripple::bvh
