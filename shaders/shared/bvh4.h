// 4-wide BVH node layout of every BVH the kernels traverse (core/bvh/Bvh4Collapse; shaders/bvh4_node.glsl):
// a binned-SAH BVH2 collapsed so that one node fetch tests four boxes. The renderer's TLAS and BLASes
// (shaders/traverse.glsl) and ripple-bench's single-level kernel (bench/kernels/shaders/traverse_bvh4.glsl)
// use it.
#ifndef RIPPLE_SHARED_BVH4_H
#define RIPPLE_SHARED_BVH4_H
#include "common.h"
#include "bvh.h"

#ifdef __cplusplus
#include <glm/vec4.hpp>
namespace ripple::gpu { using uvec4 = glm::uvec4; }
#endif

RIPPLE_GPU_BEGIN

// The four child boxes as structure of arrays (component i of each vec4 belongs to child i), so a node is
// seven 16-byte loads. children[i] is one word:
//   BVH4_EMPTY_CHILD            no child in this slot (its box is ignored)
//   BVH4_LEAF_BIT | first << 3 | (count - 1)   a leaf of `count` (1..8) primitives from leaf slot `first`
//                               (in a TLAS: the one instance at slot `first`)
//   anything else               the index of an inner node
// The same word is what the traversal pushes on its stack, so a leaf costs one stack entry, not two.
struct Bvh4Node {
    vec4 minX;
    vec4 maxX;
    vec4 minY;
    vec4 maxY;
    vec4 minZ;
    vec4 maxZ;
    uvec4 children;
};

// The same node with its child boxes quantized to 8 bits per bound in the node's own frame (after Ylitie,
// Karras and Laine 2017): 64 bytes instead of 112. Child i's box is
//   lo = frameOrigin + q_lo * scale, hi = frameOrigin + q_hi * scale   (per axis, q in 0..255)
// with scale = 2^(exponent - 127) per axis (an exact power of two, so q * scale is exact and the sum rounds
// once, the same on host and GPU). Quantization rounds lo down and hi up and is checked in float, so a
// dequantized box always contains the full one: traversal may visit more, never miss a hit.
struct Bvh4CompressedNode {
    vec4 frame;       // xyz: frame origin (the node's box lo); w: uint bits, biased exponents x | y << 8 | z << 16
    uvec4 quantX;     // x: q_lo.x of children 0..3 (byte i = child i), y: q_hi.x, z: q_lo.y, w: q_hi.y
    uvec4 quantZ;     // x: q_lo.z, y: q_hi.z, zw: 0
    uvec4 children;   // as Bvh4Node::children
};

RIPPLE_CONST uint BVH4_EMPTY_CHILD = 0xFFFFFFFFu;
RIPPLE_CONST uint BVH4_LEAF_BIT = 0x80000000u;
// Leaf slots addressable in a child word: 28 bits (first << 3 below the leaf bit). A leaf's last slot stays
// at or below this, so no leaf word equals BVH4_EMPTY_CHILD (the renderer's return-to-TLAS entry).
RIPPLE_CONST uint BVH4_MAX_LEAF_FIRST = 0x0FFFFFFFu;
// Each node visit pops one entry and pushes at most four, so the stack never holds more than three entries
// per level below the root, plus the one being expanded. Collapsing never deepens the tree.
RIPPLE_CONST uint BVH4_STACK_SIZE = 3u * BVH_MAX_DEPTH + 4u;

// Push constants of trace_closest_bvh4.comp and trace_any_bvh4.comp.
struct Bvh4TraceParams {
    uint64_t nodes;      // Bvh4Node[] (or Bvh4CompressedNode[] for the *_bvh4q kernels), root at 0
    uint64_t triangles;  // TrianglePrim[] in leaf order; v0.w holds the input triangle index as uint bits
    uint64_t rays;       // Ray[rayCount]
    uint64_t hits;       // Hit[rayCount] (closest) or uint[rayCount] (any-hit)
    uint rayCount;
    uint nodeCount;      // 0: empty mesh, every ray misses
    uint stepBudget;     // node visits + triangle tests before the ray is flagged HIT_FLAG_RAN_OUT
    uint pad0;
};

RIPPLE_GPU_END
#endif
