// One rank's share of a NanoVDB grid for data-parallel rendering: the grid's active box split by a k-d tree
// along voxel planes into one region per rank, balanced by active voxels (counted per leaf). Neighbouring
// regions share their boundary plane of voxels, as the z-slabs of a structured field do: a grid's field spans
// its active box exactly (core/scene/NanoVdbGrid.h), so each rank's field ends where its neighbour's begins,
// and linear filtering inside a region reads only the region's voxels. Each rank's grid is rebuilt with
// NanoVDB's GridBuilder from the voxels of its region (leaves, and tiles that are not background), with the
// region's corners set so that its active box is the region, and the whole grid's map.
#pragma once

#include "io/volume/NanoVdbFile.h"

#include <cstdint>

namespace ripple::apps {

// The part of `whole` that `rank` of `ranks` holds (name, world box and value range stay the whole's). One
// rank gets `whole` unchanged. The grid is read through the same checks as the device's (core/scene/
// NanoVdbTree.h). Throws std::runtime_error naming the problem: a grid those checks refuse, no active voxel,
// a region too thin to split, or non-background tiles that would fill more than 2^28 voxels of a region.
NanoVdbFile nanoVdbPart(const NanoVdbFile& whole, uint32_t rank, uint32_t ranks);

}  // namespace ripple::apps
