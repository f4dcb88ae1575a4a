// Volumes as the kernels read them: a structured-regular scalar field (voxel values as float32) seen
// through a 1D transfer function, placed in the world by an affine transform. The transfer function is a
// table of (linear RGB albedo, extinction) over the value range; a macrocell grid holds, per block of
// VOLUME_MACROCELL^3 cells, the largest extinction the field can reach there (the majorant of delta and
// ratio tracking). Built by core/scene/VolumeTable.cpp.
#ifndef RIPPLE_SHARED_VOLUME_H
#define RIPPLE_SHARED_VOLUME_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint VOLUME_MACROCELL = 8u;      // cells per macrocell edge
RIPPLE_CONST uint VOLUME_FILTER_NEAREST = 0u;
RIPPLE_CONST uint VOLUME_FILTER_LINEAR = 1u;
// Opacity o over the transfer function's unitDistance d means transmittance 1 - o over d: extinction
// -ln(1 - o) / d, infinite at o = 1, so opacity is capped at this.
RIPPLE_CONST float VOLUME_OPACITY_CAP = 0.999999f;

struct VolumeRecord {
    vec4 worldToGrid[3];   // rows of the affine map from world space to grid index space (voxel i at i)
    vec4 gridExtent;       // xyz: voxel counts minus 1 (the field spans [0, extent] in grid space); w: 0
    vec4 valueRange;       // x: lowest value, y: 1 / (highest - lowest) (0 for an empty range), zw: 0
    uint dimX;             // voxels per axis
    uint dimY;
    uint dimZ;
    uint filterMode;       // VOLUME_FILTER_*
    uint macroX;           // macrocells per axis
    uint macroY;
    uint macroZ;
    uint tableSize;        // entries of the transfer function table (>= 2)
    uint voxelOffset;      // first float of this field in SceneDesc.volumeData
    uint majorantOffset;   // first float of its macrocell majorants (world-space extinction per unit length)
    uint tableOffset;      // first float of its table: tableSize entries of 4 floats (albedo rgb, extinction)
    uint objectId;         // the application's ids for the objectId and instanceId channels (~0u: unset)
    uint instanceId;
    uint pad0;
    uint pad1;
    uint pad2;
};

RIPPLE_GPU_END
#endif
