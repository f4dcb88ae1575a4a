// NanoVDB grids (shared/volume.h VOLUME_KIND_NANOVDB): the field at a grid-space point, read through
// NanoVDB's own portable header, PNanoVDB.h (Debian's libnanovdb-dev), with its buffer reads going through
// a buffer device address. The host checked every node the tree reaches before a kernel reads it
// (core/scene/NanoVdbGrid.cpp). Voxel i's value sits at index i, as structuredRegular's does.
#ifndef RIPPLE_NANOVDB_GLSL
#define RIPPLE_NANOVDB_GLSL

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer NanoWordsRef { uint words[]; };

#define PNANOVDB_GLSL
#define PNANOVDB_BUF_CUSTOM
struct pnanovdb_buf_t {
    uint64_t address;  // the grid's first byte
};
uint pnanovdb_buf_read_uint32(pnanovdb_buf_t buf, uint byte_offset) {
    return NanoWordsRef(buf.address).words[byte_offset >> 2u];
}
uvec2 pnanovdb_buf_read_uint64(pnanovdb_buf_t buf, uint byte_offset) {
    return uvec2(pnanovdb_buf_read_uint32(buf, byte_offset), pnanovdb_buf_read_uint32(buf, byte_offset + 4u));
}
#define pnanovdb_grid_type_t uint
#define PNANOVDB_GRID_TYPE_GET(grid_typeIn, nameIn) pnanovdb_grid_type_constants[grid_typeIn].nameIn
#include "nanovdb/PNanoVDB.h"

float nanovdbVoxel(pnanovdb_buf_t buf, inout pnanovdb_readaccessor_t accessor, ivec3 ijk) {
    return pnanovdb_read_float(buf, pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, accessor, ijk));
}

// The grid at `grid` (the device address of VolumeRecord.voxels: 8 words, then the grid) at grid-space point
// g, nearest or trilinear (VOLUME_FILTER_*).
float nanovdbValue(uint64_t grid, vec3 g, uint filterMode) {
    NanoWordsRef header = NanoWordsRef(grid);
    vec3 index = g + vec3(ivec3(header.words[0], header.words[1], header.words[2]));
    pnanovdb_buf_t buf = pnanovdb_buf_t(grid + 32ul);
    pnanovdb_grid_handle_t handle;
    handle.address.byte_offset = 0u;
    pnanovdb_root_handle_t root = pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, handle));
    pnanovdb_readaccessor_t accessor;
    pnanovdb_readaccessor_init(accessor, root);
    if (filterMode == VOLUME_FILTER_NEAREST) return nanovdbVoxel(buf, accessor, ivec3(floor(index + 0.5)));
    ivec3 i0 = ivec3(floor(index));
    vec3 w = index - vec3(i0);
    float c000 = nanovdbVoxel(buf, accessor, i0), c100 = nanovdbVoxel(buf, accessor, i0 + ivec3(1, 0, 0));
    float c010 = nanovdbVoxel(buf, accessor, i0 + ivec3(0, 1, 0)), c110 = nanovdbVoxel(buf, accessor, i0 + ivec3(1, 1, 0));
    float c001 = nanovdbVoxel(buf, accessor, i0 + ivec3(0, 0, 1)), c101 = nanovdbVoxel(buf, accessor, i0 + ivec3(1, 0, 1));
    float c011 = nanovdbVoxel(buf, accessor, i0 + ivec3(0, 1, 1)), c111 = nanovdbVoxel(buf, accessor, i0 + ivec3(1, 1, 1));
    return mix(mix(mix(c000, c100, w.x), mix(c010, c110, w.x), w.y), mix(mix(c001, c101, w.x), mix(c011, c111, w.x), w.y), w.z);
}

#endif
