// Brute-force CPU ray tracer in double precision: the ground truth that GPU traversal results are checked
// against. It skips exactly the primitives and instances core::Scene skips, so a skipped one is never hit.
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/ray.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace ripple::test {

// Two hits closer than this (relative to the nearest t) are a tie: the GPU may legitimately report any of them.
inline constexpr double kTieRelativeTolerance = 1e-9;
// An instance whose upper 3x3 has |det| at or below this is singular and skipped, as core::Scene does.
inline constexpr double kSingularDeterminant = 1e-30;

struct RefHit {
    bool found = false;
    double t = std::numeric_limits<double>::infinity();
    uint32_t instanceId = ~0u;  // index in SceneDescription::instances
    uint32_t primId = ~0u;      // index of the triangle or sphere in its mesh or sphere set (input numbering)
    double u = 0.0;             // barycentrics of v1 and v2 for triangles; 0 for spheres (as gpu::Hit)
    double v = 0.0;
    int hitCount = 0;           // primitives hit within kTieRelativeTolerance of t (1 = unique, 0 = miss)
};

// ---- The validity rules of core::Scene, one small function each so tests can count what must be skipped.

// Triangles of a mesh: indices.size(), or positions.size() / 3 when indices is empty (trailing
// positions that do not make a full triple are ignored).
uint32_t triangleCount(const core::TriangleMesh& mesh);
// Vertex indices of triangle `tri`; unchecked, they may be out of range.
glm::uvec3 triangleIndices(const core::TriangleMesh& mesh, uint32_t tri);
bool isFinite(const glm::vec3& v);
// False for a non-finite vertex, an index out of range, or zero area (cross product exactly 0 in double).
bool isTriangleValid(const core::TriangleMesh& mesh, uint32_t tri);

uint32_t sphereCount(const core::SphereSet& set);
// radii[i] when there is one radius per center, radii[0] when there is a single one, otherwise 0: a set
// with any other radius count is skipped whole (as core::Scene does).
float sphereRadius(const core::SphereSet& set, uint32_t i);
// False for a non-finite center or a radius that is <= 0 or non-finite.
bool isSphereValid(const core::SphereSet& set, uint32_t i);

// Cylinders of a set: indices.size(), or positions.size() / 2 when indices is empty.
uint32_t cylinderCount(const core::CylinderSet& set);
// End indices of cylinder i; unchecked, they may be out of range.
glm::uvec2 cylinderIndices(const core::CylinderSet& set, uint32_t i);
// As sphereRadius: one per cylinder, a single one for all, otherwise 0 (the whole set is skipped).
float cylinderRadius(const core::CylinderSet& set, uint32_t i);
// False for an index out of range, a NaN or Inf end, a radius that is <= 0 or non-finite, or an axis
// whose squared float length is below FLT_MIN (zero length).
bool isCylinderValid(const core::CylinderSet& set, uint32_t i);

// False when any of the 16 entries is non-finite, the bottom row is not (0, 0, 0, 1), or
// |det(upper 3x3)| <= kSingularDeterminant: the rule of core::Scene.
bool isTransformValid(const glm::mat4& objectToWorld);
// False for an unknown kind or an index out of range; otherwise whether at least one primitive is valid
// (geometry left empty by validation cannot hold a BLAS). O(primitives).
bool hasValidPrimitive(const core::SceneDescription& scene, const core::GeometryRef& geometry);
bool isInstanceValid(const core::SceneDescription& scene, const core::InstanceDescription& instance);

// ---- Tracing.
//
// Ray semantics follow gpu::Ray: origin.w is tmin, direction.w is tmax, the direction need not be unit
// length and t is measured in units of it; a hit counts when tmin < t < tmax (open interval). The ray is
// taken to object space with the inverse instance transform in double, without renormalising the
// direction, so t is the same in both spaces. Rays with a non-finite origin, direction or tmin, or a zero direction, miss.
//
// Triangles use the watertight test of Woop, Benthin and Wald (JCGT 2013) in double: vertices are
// sheared into the ray's frame, and the 2D edge functions get exact signs (an error-bound filter, then
// an exact expansion). A closed mesh with shared vertices therefore has no cracks here, at edges or at
// vertices, whatever the rounding. Edges and vertices count as inside, so a ray through a shared edge or
// vertex hits every triangle around it (a tie). No back-face culling.
// Spheres use the quadratic of Haines et al. (Ray Tracing Gems, ch. 7) and report the nearest root
// above tmin, i.e. the far root for rays starting inside. Cylinders solve the same quadratic across the
// axis, keep side hits between the ends, add the cap disks when the set has caps, and report u = the
// axial fraction (0 at the first end) and v = 0 on the side, 1 on a cap (as gpu::Hit).
//
// Among exact ties the lowest (instanceId, primId) wins; among near ties (hitCount > 1) a GPU answer
// should be accepted if it matches any of them.

// Validates and converts the scene to double once, so many rays can be traced without redoing it.
class ReferenceScene {
public:
    explicit ReferenceScene(const core::SceneDescription& scene);

    RefHit traceClosest(const gpu::Ray& ray) const;
    bool traceAny(const gpu::Ray& ray) const;

    // Parallel over rays with oneTBB. Brute force: cost is rays x primitives (over all instances), about
    // 10 ns per triangle test and 2 ns per sphere test per core, so keep it to small scenes: 20k triangles
    // x 4k rays takes ~0.7 s on 2 cores, the 1M-triangle grid ~10 ms per ray per core.
    std::vector<RefHit> traceClosest(std::span<const gpu::Ray> rays) const;
    std::vector<uint8_t> traceAny(std::span<const gpu::Ray> rays) const;

    uint64_t validTriangleCount() const { return validTriangles_; }
    uint64_t validSphereCount() const { return validSpheres_; }
    uint64_t validCylinderCount() const { return validCylinders_; }
    uint32_t validInstanceCount() const { return static_cast<uint32_t>(instances_.size()); }

private:
    struct Triangle { glm::dvec3 a, b, c; uint32_t primId; };
    struct Sphere { glm::dvec3 center; double radius; uint32_t primId; };
    struct Cylinder { glm::dvec3 a, b; double radius; uint32_t primId; uint32_t caps; };
    struct Cone { glm::dvec3 a, b; double ra, rb; uint32_t primId; uint32_t caps; bool round; };
    struct Instance {
        glm::dmat3 worldToObject;   // inverse of the linear part
        glm::dvec3 translation;     // object-to-world translation
        core::GeometryKind kind;
        uint32_t geometry;          // index into meshes_, sphereSets_ or cylinderSets_
        uint32_t instanceId;
    };

    template <typename Visit> void forEachHit(const gpu::Ray& ray, Visit&& visit) const;

    std::vector<std::vector<Triangle>> meshes_;     // valid triangles only, per input mesh
    std::vector<std::vector<Sphere>> sphereSets_;   // valid spheres only, per input sphere set
    std::vector<std::vector<Cylinder>> cylinderSets_; // valid cylinders only, per input cylinder set
    std::vector<std::vector<Cone>> coneSets_;       // valid cones and curve segments, per input cone set
    std::vector<Instance> instances_;               // valid instances only, in input order
    uint64_t validTriangles_ = 0;
    uint64_t validSpheres_ = 0;
    uint64_t validCylinders_ = 0;
};

// One-shot conveniences; each builds a ReferenceScene, so prefer the class (or the *All forms) for many rays.
RefHit traceClosest(const core::SceneDescription& scene, const gpu::Ray& ray);
bool traceAny(const core::SceneDescription& scene, const gpu::Ray& ray);
std::vector<RefHit> traceClosestAll(const core::SceneDescription& scene, std::span<const gpu::Ray> rays);
std::vector<uint8_t> traceAnyAll(const core::SceneDescription& scene, std::span<const gpu::Ray> rays);

}  // namespace ripple::test
