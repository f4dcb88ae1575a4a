// Volumes as the kernels read them: a structured-regular scalar field (voxel values as float32) seen
// through a 1D transfer function, placed in the world by an affine transform. The transfer function is a
// table of (linear RGB albedo, extinction) over the value range, followed by a range-maximum table of its
// extinction; a macrocell grid holds, per block of VOLUME_MACROCELL^3 cells, the largest extinction the
// field can reach there (the majorant of delta and ratio tracking). Built by core/scene/VolumeTable.cpp
// and, for the majorants, core/scene/VolumeMajorants.cpp.
#ifndef RIPPLE_SHARED_VOLUME_H
#define RIPPLE_SHARED_VOLUME_H
#include "common.h"
#include "ray.h"

RIPPLE_GPU_BEGIN

// Cells per macrocell edge.
RIPPLE_CONST uint VOLUME_MACROCELL = 8u;
// A macrocell of a linearly filtered volume whose majorant's optical depth over one cell crossing reaches
// this is crossed cell by cell, under majorants from the interpolant along the ray (shaders/volume.glsl).
RIPPLE_CONST float VOLUME_REFINE_DEPTH = 1.0f;
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
    uint majorantOffset;   // first float of the macrocell majorants in SceneDesc.volumeData (world-space
                           // extinction per unit length)
    uint tableOffset;      // first float of its table there: tableSize entries of 4 floats (albedo rgb, extinction),
                           // then its range-maximum table: level k (0 .. floor(log2(tableSize))) holds tableSize
                           // floats, entry i the largest extinction of entries i .. min(i + 2^k, tableSize) - 1
    uint objectId;         // the application's ids for the objectId and instanceId channels (~0u: unset)
    uint instanceId;
    uint64_t voxels;       // device address of the field's float values (a buffer of its own, which a later
                           // scene reuses while the field is unchanged)
    uint cellByCell;       // 1: some macrocell may be crossed cell by cell (VOLUME_REFINE_DEPTH), so the kernels
                           // take the march that can; 0: none can (set with the majorants)
    uint kind;             // VOLUME_KIND_*. Unstructured: `voxels` is the mesh (UnstructuredHeader and what it
                           // indexes); the grid is a virtual one of macrocells over the mesh's box, whose
                           // majorants the host fills (core/scene/UnstructuredGrid.h); dim* are the macrocells
                           // times VOLUME_MACROCELL plus 1; filterMode and cellByCell are unused (0)
};

RIPPLE_CONST uint VOLUME_KIND_STRUCTURED = 0u;
RIPPLE_CONST uint VOLUME_KIND_UNSTRUCTURED = 1u;
// A NanoVDB grid: `voxels` is 8 words (the index of grid space's origin, x y z) and then the grid, read with
// PNanoVDB.h (shaders/nanovdb.glsl); the grid is a virtual one of macrocells over its active box, whose
// majorants the host fills (core/scene/NanoVdbGrid.h); filterMode as for structured grids.
RIPPLE_CONST uint VOLUME_KIND_NANOVDB = 2u;
// A block-structured AMR hierarchy: `voxels` is the AmrHeader and what it indexes; the grid is a virtual one
// of macrocells over the blocks' box, whose majorants the host fills (core/scene/AmrGrid.h); filterMode and
// cellByCell are unused (0): the value is the finest covering cell's.
RIPPLE_CONST uint VOLUME_KIND_AMR = 3u;

// An unstructured mesh on the device: 32-bit words from the address VolumeRecord.voxels, this header first.
// Vertices are in the volume's grid space (the record's worldToGrid applies to rays, not to vertices).
// Cells are in the order of the BVH's leaves; a cell's word is its first index << 2 | its shape
// (UNSTRUCTURED_TETRAHEDRON..), whose corners are indices[first ..] in VTK's vertex order. A point query
// starts at its start cell's node: the lowest node whose subtree holds every cell overlapping the start
// cell (UNSTRUCTURED_NO_NODE: no cell does). In a mesh with tetrahedra it first walks from its start cell's
// tetrahedron across shared faces: with `neighbours`, a tetrahedron's 4 indices are followed by the leaf-order
// cells across the faces opposite its corners 0..3 (UNSTRUCTURED_NO_CELL: none, a boundary face, or a cell
// that is not a tetrahedron).
struct UnstructuredHeader {
    uint cellCount;
    uint nodeCount;        // BvhNodes (shared/bvh.h) at nodeOffset; 0: no cell
    uint vertexOffset;     // a vec4 per vertex: position, and its value (0 when cellCentered); a multiple of 4
    uint cellValueOffset;  // cellCentered: a float per cell, in leaf order
    uint cellOffset;       // a word per cell
    uint indexOffset;      // vertex indices
    uint nodeOffset;       // a multiple of 4 (the nodes are read as vec4s)
    uint cellCentered;
    uint startOffset;      // a word per start cell (x fastest)
    uint startX;           // start cells per axis: startPerMacrocell per macrocell edge
    uint startY;
    uint startZ;
    uint startPerMacrocell;
    uint neighbours;       // UNSTRUCTURED_NEIGHBOURS_*
    uint startCellOffset;  // with neighbours: a word per start cell, the tetrahedron its walks begin at
};

// An AMR hierarchy on the device: 32-bit words from the address VolumeRecord.voxels, this header first. Block
// b is AmrBlockRecord b at blockOffset; macrocell m's blocks (those overlapping it, finest level first) are
// the block indices entries[lists[2m] .. lists[2m] + lists[2m + 1]) with lists at listOffset and entries at
// entryOffset.
struct AmrHeader {
    uint blockCount;
    uint blockOffset;
    uint listOffset;
    uint entryOffset;
};

// A block in grid space: its cells are cubes of side cellSize from `lower`, dims per axis, their values the
// floats at word firstValue (x fastest).
struct AmrBlockRecord {
    float lowerX;
    float lowerY;
    float lowerZ;
    float cellSize;
    uint dimX;
    uint dimY;
    uint dimZ;
    uint firstValue;
};

RIPPLE_CONST uint UNSTRUCTURED_NO_NODE = 0xFFFFFFFFu;
RIPPLE_CONST uint UNSTRUCTURED_NO_CELL = 0xFFFFFFFFu;
// UnstructuredHeader.neighbours: none (no tetrahedron); tetrahedra's indices followed by their neighbours;
// the same in a mesh of tetrahedra only, whose cell c's 8 words then start at index word 8c.
RIPPLE_CONST uint UNSTRUCTURED_NEIGHBOURS_NONE = 0u;
RIPPLE_CONST uint UNSTRUCTURED_NEIGHBOURS_SOME_TETRAHEDRA = 1u;
RIPPLE_CONST uint UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA = 2u;
RIPPLE_CONST uint UNSTRUCTURED_TETRAHEDRON = 0u;  // VTK 10
RIPPLE_CONST uint UNSTRUCTURED_HEXAHEDRON = 1u;   // VTK 12
RIPPLE_CONST uint UNSTRUCTURED_WEDGE = 2u;        // VTK 13
RIPPLE_CONST uint UNSTRUCTURED_PYRAMID = 3u;      // VTK 14

// Push constants of volume_majorants.comp: the majorants of macrocells firstCell.. of one volume.
struct MajorantParams {
    uint64_t volumes;      // VolumeRecord[]
    uint64_t volumeData;   // the floats VolumeRecord's offsets index (SceneDesc.volumeData)
    uint volume;           // which record
    uint firstCell;        // macrocell of invocation 0 (a grid may need more than one dispatch)
};

// Marches that spend their step budget (pt_volume, pt_shadow_volume) are parked with their state and
// resumed by further dispatches, never ended with a wrong answer: see core/render/VolumeParking.h.
RIPPLE_CONST uint VOLUME_MAX_RESUME_ROUNDS = 31u;

// A parked march: enough to continue from where it stopped. Pool `round & 1` holds those parked in `round`.
struct VolumeParked {
    uint ray;              // the item's index in the stage's queue (or batch of visiting rays)
    uint volume;           // the volume whose march spent the budget; volumes before it are done
    float t;               // where along the ray that march stopped
    float tEnd;            // pt_volume: the nearest collision so far, else where the ray ends (surface or tmax)
    vec4 albedo;           // pt_volume: rgb the albedo at that collision; w unused
    float transmittance;   // pt_shadow_volume: the product over the volumes so far
    uint collidedVolume;   // pt_volume: the volume of that collision; ~0u: none yet
    uint pad0;
    uint pad1;
};

// Head of the parking buffer, followed by 2 * capacity VolumeParked (pool 0, then pool 1). parked[r]
// counts the marches round r parked and is the indirect dispatch of round r + 1 (all zeroed before a stage).
struct VolumeParkingHeader {
    ResumeHeader parked[VOLUME_MAX_RESUME_ROUNDS + 1u];
    uint capacity;         // entries per pool
    uint stepBudget;       // tracking steps (macrocell crossings plus tentative collisions) per invocation
    uint lastRound;        // the last resume round: it parks nothing (a march still unfinished is flagged)
    uint pad0;
};

RIPPLE_GPU_END
#endif
