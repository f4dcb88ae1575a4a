// Scenes for the data-parallel tests, each split over ranks as an application would: part(rank, ranks)
// holds only what that rank owns, and part(0, 1) is the whole scene. Lights sit on rank 0 alone (the
// device gathers them), so every other rank's shading depends on the gather.
#pragma once

#include "core/render/PathTracer.h"
#include "core/scene/SceneDescription.h"

#include <cstdint>

namespace ripple::test {

// The paper's 4x4x4 boxes over a floor, under a point and a directional light; boxes are dealt to the
// ranks by a fixed pseudo-random permutation, so most shadows and bounces cross rank boundaries. The
// floor belongs to the last rank.
core::SceneDescription boxesPart(uint32_t rank, uint32_t ranks);
core::Camera boxesCamera();

// A heterogeneous scattering volume (a smooth blob, 33^3 samples over [-2, 2]^2 x [0, 4]) split into
// slabs along x, one per rank, each with the sample plane it shares with its neighbour (so linear
// filtering matches across the faces), over a floor on the last rank, two boxes on rank 0 and a sun.
core::SceneDescription volumePart(uint32_t rank, uint32_t ranks);
core::Camera volumeCamera();
// The same blob's iso-surfaces at 0.25 and 0.6 (coloured per isovalue), split into the same slabs, in the
// same surroundings; seen through volumeCamera().
core::SceneDescription isosurfacePart(uint32_t rank, uint32_t ranks);

// Mixed geometry (a sphere mesh, spheres, cylinders, a metal and a transparent material) under a quad
// light, instances dealt round robin.
core::SceneDescription mixedPart(uint32_t rank, uint32_t ranks);
core::Camera mixedCamera();

}  // namespace ripple::test
