// Meshes ripple-bench makes itself, so a run needs no files: a bumpy sphere built from a subdivided cube.
#pragma once

#include "core/scene/SceneDescription.h"

#include <cstdint>

namespace ripple::bench {

// A cube whose six faces are split into n x n quads (12 n^2 triangles), projected to the unit sphere and
// displaced radially by a few sine octaves, so secondary rays meet crevices rather than a convex ball.
// Vertices on shared cube edges are computed from the same grid values and are bitwise equal: no cracks.
core::TriangleMesh displacedCubeSphere(uint32_t n);

// "builtin": about 100k triangles (the README's default run); "procedural": at least 2^20 triangles.
inline constexpr uint32_t kBuiltinSubdivision = 92;      // 101,568 triangles
inline constexpr uint32_t kProceduralSubdivision = 296;  // 1,051,392 triangles

}  // namespace ripple::bench
