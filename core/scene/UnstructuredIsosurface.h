// Iso-surfaces of unstructured fields (ANARI geometry "isosurface" on an "unstructured" field) as triangles.
// In a tetrahedron the field is linear, so its surface of equal value is exactly a plane polygon: marching
// tetrahedra gives it without error (a triangle or a quad as two). Hexahedra, wedges and pyramids are cut
// into tetrahedra first (6 around the 0-6 diagonal, 3 and 2), so their surface is that of the piecewise-
// linear field of the cut: exact where the field is linear, otherwise within the cut's interpolation error
// of the trilinear (wedge, pyramid) surface, and neighbouring cells cut along different face diagonals may
// leave cracks of that size between them.
#pragma once

#include "core/scene/SceneDescription.h"
#include "core/scene/UnstructuredGrid.h"

#include <vector>

namespace ripple::core {

// The surfaces of `cells` (vertex values) at each of `isovalues`, each triangle facing the way the field
// increases; triangle t belongs to isovalue isovalueOf[t]. Cells checked by prepareUnstructuredGrid only.
struct UnstructuredIsosurface {
    TriangleMesh mesh;                    // positions only: three per triangle
    std::vector<uint32_t> isovalueOf;
};

UnstructuredIsosurface extractIsosurface(const UnstructuredCells& cells, const std::vector<float>& isovalues);

}  // namespace ripple::core
