// Buffer views of the trace primitives of shared/scene.h (SceneDesc.triangles, spheres, cylinders, cones,
// isoCells), shared by the traversal kernels and the surface reconstruction.
#ifndef RIPPLE_PRIMITIVE_REFS_GLSL
#define RIPPLE_PRIMITIVE_REFS_GLSL
#include "shared/scene.h"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TrianglesRef { TrianglePrim triangles[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SpheresRef { SpherePrim spheres[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer CylindersRef { CylinderPrim cylinders[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ConesRef { ConePrim cones[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer IsoCellsRef { IsoCellPrim cells[]; };

#endif
