// One rank's share of an AMR hierarchy for data-parallel rendering: the hierarchy's box split by a k-d tree
// into one region per rank, along cell faces of its coarsest level, balanced by cell count; each rank keeps
// every block clipped to its region. Regions do not overlap and every cell of every level lies in exactly
// one, so the finest cell covering a point on the rank that holds it is the whole hierarchy's finest cell
// there: N ranks draw the field one rank draws.
#pragma once

#include "io/vtk/VtkAmrFile.h"

#include <cstdint>
#include <utility>

namespace ripple::apps {

// The part of `whole` that `rank` of `ranks` holds (origin, spacing, cell widths, array name and value range
// stay the whole's). One rank gets `whole` unchanged. Throws std::runtime_error when the hierarchy cannot be
// split so: a level whose cell width does not divide the coarsest level's, or fewer coarse cells along the
// axes than ranks need, or a region with no cell.
AmrData amrPart(const AmrData& whole, uint32_t rank, uint32_t ranks);

// The object-space box of `amr`'s blocks: lowest corner, highest corner.
std::pair<glm::dvec3, glm::dvec3> amrBounds(const AmrData& amr);

}  // namespace ripple::apps
