// One geometry after validation and BLAS construction: which input primitives are kept, their BVH, and
// what was skipped. Immutable once built, so a later Scene can share it (see Scene's `previous`).
#pragma once

#include "core/bvh/BinnedSahBuilder.h"
#include "core/bvh/Bvh4Collapse.h"
#include "core/scene/SceneDescription.h"

#include <memory>
#include <string>
#include <vector>

namespace ripple::core {

struct PreparedGeometry {
    GeometryKind kind = GeometryKind::Triangles;
    GeometryIdentity identity;
    bvh::BuildOptions buildOptions;     // the BLAS is only reused under the same options
    std::vector<uint32_t> validPrims;   // input indices of the kept primitives
    bvh::Bvh blas;                      // over validPrims; blas.primOrder indexes validPrims. Its BVH2
                                        // nodes are dropped once collapsed: only blas4 is traced
    bvh::Bvh4 blas4;                    // blas collapsed 4 wide (the kernels' layout), reused with it
    uint64_t inputPrimCount = 0;
    uint64_t positionCount = 0;         // positions (or centers, or voxels) it was validated against
    // Isosurfaces only: the primitives are the (cell, isovalue) pairs where the surface crosses a cell,
    // each stored as cell * isovalues + isovalue index (cells numbered x fastest over dims - 1).
    std::vector<uint64_t> isoCells;
    uint64_t skipped = 0;
    // Why primitives were skipped, without the geometry's name (which depends on where it sits in a
    // description, so it is added when reported).
    std::vector<std::string> problems;
};

// "mesh 3", "sphere set 0", "cylinder set 2": how reports name a geometry.
std::string geometryLabel(GeometryKind kind, uint32_t index);

// Primitive count of a geometry as the input defines it (before validation).
uint64_t primitiveCount(const TriangleMesh& mesh);
uint64_t primitiveCount(const SphereSet& set);
uint64_t primitiveCount(const CylinderSet& set);
uint64_t primitiveCount(const ConeSet& set);

// The radius of sphere or cylinder i: one per primitive or a single one for all (the caller checked
// that radii has one of these two lengths).
inline float radiusOf(const std::vector<float>& radii, uint64_t i) { return radii.size() == 1 ? radii[0] : radii[i]; }
// Endpoints of cylinder or cone i (indices unchecked).
glm::uvec2 cylinderIndices(const CylinderSet& set, uint64_t i);
glm::uvec2 coneIndices(const ConeSet& set, uint64_t i);
// Bounds of a cone frustum (or of the two spheres of a round segment), never smaller than the shape.
bvh::Aabb coneBox(const glm::vec3& a, float ra, const glm::vec3& b, float rb, bool round);

// Whether `prepared` fits the geometry's current arrays well enough to be used without reading out of
// range: same counts, and every kept primitive's indices within the positions. A reused geometry whose
// identity was not updated after a change may then render wrongly, but never crashes.
bool fits(const PreparedGeometry& prepared, const TriangleMesh& mesh);
bool fits(const PreparedGeometry& prepared, const SphereSet& set);
bool fits(const PreparedGeometry& prepared, const CylinderSet& set);
bool fits(const PreparedGeometry& prepared, const ConeSet& set);
bool fits(const PreparedGeometry& prepared, const IsosurfaceSet& set);

// Validates the primitives of one geometry and builds its BLAS. Skips (and names in `problems`) NaN or
// Inf positions, indices out of range, zero-area triangles, zero-length cylinders and radii that are not
// finite and positive.
std::shared_ptr<const PreparedGeometry> prepareGeometry(const TriangleMesh& mesh, const bvh::BuildOptions& options);
std::shared_ptr<const PreparedGeometry> prepareGeometry(const SphereSet& set, const bvh::BuildOptions& options);
std::shared_ptr<const PreparedGeometry> prepareGeometry(const CylinderSet& set, const bvh::BuildOptions& options);
// Cones and curve segments: also skips radii that are negative or not finite, and cones whose both radii
// are 0.
std::shared_ptr<const PreparedGeometry> prepareGeometry(const ConeSet& set, const bvh::BuildOptions& options);
// Iso-surfaces: one primitive per cell and isovalue that the surface crosses (the cell's corner values
// span the isovalue), so the BLAS over them skips every cell the surface does not enter. Cells with a
// NaN or Inf corner are skipped; a field whose dims, values or spacing do not fit skips the whole set.
std::shared_ptr<const PreparedGeometry> prepareGeometry(const IsosurfaceSet& set, const bvh::BuildOptions& options);

}  // namespace ripple::core
