// Block-structured AMR hierarchies (shared/volume.h AmrHeader, packed by core/scene/AmrGrid.cpp): the field
// at a grid-space point is the value of the finest cell that covers it. The point's macrocell lists the
// blocks overlapping it, finest level first; the first that holds the point gives the value.
#ifndef RIPPLE_AMR_GLSL
#define RIPPLE_AMR_GLSL

#include "shared/volume.h"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer AmrWordsRef { uint words[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer AmrBlocksRef { AmrBlockRecord blocks[]; };

// The value at grid-space point g of the hierarchy at `amr` (VolumeRecord.voxels) over `macrocells` per axis;
// false where no block holds g.
bool amrValue(uint64_t amr, uvec3 macrocells, vec3 g, out float value) {
    value = 0.0;
    AmrWordsRef w = AmrWordsRef(amr);
    ivec3 cell = ivec3(floor(g / float(VOLUME_MACROCELL)));
    if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(macrocells)))) return false;
    uint listOffset = w.words[2u], entryOffset = w.words[3u];
    AmrBlocksRef blocks = AmrBlocksRef(amr + 4ul * uint64_t(w.words[1u]));
    uint list = listOffset + 2u * ((uint(cell.z) * macrocells.y + uint(cell.y)) * macrocells.x + uint(cell.x));
    uint first = w.words[list], count = w.words[list + 1u];  // at most 65,535 (the host checks)
    for (uint e = first; e < first + count; ++e) {
        AmrBlockRecord b = blocks.blocks[w.words[entryOffset + e]];
        ivec3 c = ivec3(floor((g - vec3(b.lowerX, b.lowerY, b.lowerZ)) / b.cellSize));
        uvec3 dims = uvec3(b.dimX, b.dimY, b.dimZ);
        if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(dims)))) continue;
        value = uintBitsToFloat(w.words[b.firstValue + (uint(c.z) * dims.y + uint(c.y)) * dims.x + uint(c.x)]);
        return true;
    }
    return false;
}

#endif
