// Deterministic test scenes and rays: random soups, degenerate meshes, a watertight perturbed sphere, large
// grids, instanced copies, far-from-origin offsets. The same seed gives the same output on every platform.
#pragma once

#include "core/bvh/Aabb.h"
#include "core/scene/SceneDescription.h"
#include "shaders/shared/ray.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace ripple::test {

// ---- Scenes

// A scene holding just this geometry under one identity instance.
core::SceneDescription sceneOf(core::TriangleMesh mesh);
core::SceneDescription sceneOf(core::SphereSet spheres);
core::SceneDescription sceneOf(core::CylinderSet cylinders);

// World-space bounds of the valid instances' valid primitives (spheres and cylinders by their boxes);
// empty if none.
bvh::Aabb worldBounds(const core::SceneDescription& scene);

// `count` non-indexed triangles inside the box [-extent, extent]^3, each about as large as the spacing
// between them (2 * extent / cbrt(count)), so they overlap moderately.
core::TriangleMesh randomTriangleSoup(uint32_t count, uint32_t seed, float extent = 1.0f);

// Triangle order of degenerateAndNeedleMesh: the groups come in this order and these sizes, so a test
// knows which triangles the scene must keep (normal, needle, sliver) and skip (coincident, collinear).
struct DegenerateMeshLayout {
    static constexpr uint32_t normal = 64;      // ordinary triangles
    static constexpr uint32_t needles = 64;     // two long edges and one 1e-6 times shorter; nonzero area
    static constexpr uint32_t coincident = 32;  // two equal vertices (half by repeated index, half by value)
    static constexpr uint32_t collinear = 32;   // three distinct, exactly collinear vertices
    static constexpr uint32_t slivers = 64;     // long edges, height 1e-4 of the base; nonzero area
    static constexpr uint32_t total = normal + needles + coincident + collinear + slivers;
    static constexpr uint32_t kept = normal + needles + slivers;
};
// Indexed mesh within [-1, 1]^3 laid out as DegenerateMeshLayout says. Needles and slivers are verified
// to have nonzero area in double (isTriangleValid), coincident and collinear ones exactly zero.
core::TriangleMesh degenerateAndNeedleMesh(uint32_t seed);

// `count` spheres with centers in [-extent, extent]^3 and radii in [minRadius, maxRadius], one radius each.
core::SphereSet randomSpheres(uint32_t count, uint32_t seed, float extent = 1.0f, float minRadius = 0.01f,
                              float maxRadius = 0.1f);

// `count` non-indexed cylinders with centers in [-extent, extent]^3, random axis directions, lengths in
// [minLength, maxLength] and radii in [minRadius, maxRadius], one radius each.
core::CylinderSet randomCylinders(uint32_t count, uint32_t seed, bool caps, float extent = 1.0f,
                                  float minRadius = 0.01f, float maxRadius = 0.1f, float minLength = 0.05f,
                                  float maxLength = 0.5f);

// A closed unit sphere: an icosahedron subdivided `subdivisions` times (20 * 4^s triangles), vertices shared
// through indices, each moved radially by a factor in [1 - perturbation, 1 + perturbation]. Outward
// winding. Watertight by construction: every edge joins two triangles that reference the same vertices.
core::TriangleMesh perturbedSphereMesh(uint32_t subdivisions, uint32_t seed, float perturbation = 0.1f);

// True when every edge (by vertex index) is used by exactly two triangles, in opposite directions (closed
// and consistently oriented), and no triangle repeats or misses an index. Topological only: a
// non-indexed mesh shares no indices and is never closed.
bool isClosedManifold(const core::TriangleMesh& mesh);

// A height field over [-size/2, size/2]^2 in the xz plane (y up, heights within +-amplitude), indexed, with
// at least `trianglesAtLeast` triangles. Built in one pass: about 20 ms per million triangles.
core::TriangleMesh gridMesh(uint32_t trianglesAtLeast, float size = 2.0f, float amplitude = 0.05f);

// `copies` instances of each instance of `base` (or of each geometry, when base has no instances), each
// under a random affine transform: rotation, per-axis scale in [0.5, 2], translation in
// [-spread, spread]^3, applied after the base instance's own transform. Geometry is shared, not copied.
// Instances are ordered copy-major: instance k * baseCount + i is copy k of base instance i.
core::SceneDescription instancedCopies(const core::SceneDescription& base, uint32_t copies, uint32_t seed,
                                       float spread = 4.0f);

// Moves every mesh vertex, sphere center and cylinder end by `delta` in object space (float arithmetic, so far offsets
// round the geometry as a real far-away scene would be). It is a world translation by `delta` whenever the
// instances' linear parts are identity, as in sceneOf(); instance transforms are left alone.
core::SceneDescription offset(const core::SceneDescription& scene, const glm::vec3& delta);
// World translation by pre-multiplying every instance transform; geometry stays near its origin.
core::SceneDescription offsetInstances(const core::SceneDescription& scene, const glm::vec3& delta);

// ---- Rays. All have tmin = 0 and tmax = +inf unless said otherwise.

// Origins uniform in [lo, hi] enlarged by a quarter of its size on every side, unit directions uniform on
// the sphere.
std::vector<gpu::Ray> randomRays(uint32_t count, uint32_t seed, const glm::vec3& lo, const glm::vec3& hi);

// Rays from random origins in the enlarged world bounds toward random points on random valid primitives,
// so nearly all hit something (empty when the scene has nothing valid). With normalised = false the direction is target - origin (t ~ 1 at the
// target), which exercises non-unit directions.
std::vector<gpu::Ray> raysTowardPoints(const core::SceneDescription& scene, uint32_t count, uint32_t seed,
                                       bool normalised = true);

// Unit rays in uniformly random directions from `center`, each origin jittered uniformly within a ball of
// radius `jitter`: for closed meshes around the center, every one must hit.
std::vector<gpu::Ray> raysFromInside(const glm::vec3& center, uint32_t count, uint32_t seed, float jitter = 0.0f);

// The same rays with origins moved by `delta` (to follow offset()).
std::vector<gpu::Ray> offsetRays(std::span<const gpu::Ray> rays, const glm::vec3& delta);

}  // namespace ripple::test
