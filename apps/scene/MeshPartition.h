// One rank's share of an unstructured mesh for data-parallel rendering: the cells split by a k-d tree over
// their centroids into one spatially coherent region per rank, balanced by count, each part keeping only
// the vertices its cells use. Every cell goes to exactly one rank, so the ranks' fields add up to the whole
// (their boxes may overlap where cells stick out of a region; the ray exchange visits every rank whose box a
// ray crosses).
#pragma once

#include "io/vtk/VtkUnstructuredFile.h"

#include <cstdint>

namespace ripple::apps {

// The part of `whole` that `rank` of `ranks` holds (minValue, maxValue and warnings stay the whole's). One
// rank gets `whole` unchanged.
UnstructuredMesh meshPart(const UnstructuredMesh& whole, uint32_t rank, uint32_t ranks);

}  // namespace ripple::apps
