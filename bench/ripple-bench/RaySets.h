// The three ray sets ripple-bench traces: primary rays of a pinhole camera framing the mesh, and from the
// reference primary hits, shadow rays toward a point light and one cosine-weighted diffuse bounce.
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/ray.h"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace ripple::bench {

// Rays are unbounded in practice but kept finite: Vulkan only promises Inf survives shader arithmetic
// where shaderSignedZeroInfNanPreserve is set, and the same arrays go to both tracers.
inline constexpr float kRayFar = 1e30f;
// Secondary origins move off the surface by this fraction of the scene's bounding-box diagonal.
inline constexpr float kOffsetRelative = 1e-4f;

struct Bounds {
    glm::vec3 lo{0.0f};
    glm::vec3 hi{0.0f};
    float diagonal() const { return glm::length(hi - lo); }
};

Bounds meshBounds(const core::TriangleMesh& mesh);

// One ray per pixel centre, row-major from the top-left pixel; unit directions, so t is a distance.
// The camera looks at the box centre from the front, a little from above and the right, from the
// nearest point where the whole box fits the 45-degree vertical field of view.
std::vector<gpu::Ray> primaryRays(const Bounds& bounds, uint32_t width, uint32_t height);

// Above the scene, off-centre so shadows fall sideways and are visible in any view.
glm::vec3 lightPosition(const Bounds& bounds);

struct SecondaryRays {
    std::vector<gpu::Ray> shadow;  // origin -> light: t in [0, 1] covers the segment exactly
    std::vector<gpu::Ray> bounce;  // unit cosine-weighted directions about the normal, t in [0, kRayFar]
    std::vector<uint32_t> source;  // the primary ray each pair starts from
};

// One shadow and one bounce ray per primary ray whose `hits` entry is a clean hit (status exactly
// HIT_FOUND, primId in range); misses and flagged rays are left out. The hit point is rebuilt from the triangle and the
// barycentrics, and offset along the geometric normal turned toward the incoming ray. Deterministic:
// the bounce direction of a ray depends only on its primary index and `seed`.
SecondaryRays secondaryRays(const core::TriangleMesh& mesh, const Bounds& bounds, std::span<const gpu::Ray> primary,
                            std::span<const gpu::Hit> hits, uint32_t seed = 1);

}  // namespace ripple::bench
