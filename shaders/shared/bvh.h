// Binary BVH node layout the builder produces (core/bvh/BinnedSahBuilder); every BVH is collapsed to the
// 4-wide layout of bvh4.h (core/bvh/Bvh4Collapse) before the kernels see it.
#ifndef RIPPLE_SHARED_BVH_H
#define RIPPLE_SHARED_BVH_H
#include "common.h"

RIPPLE_GPU_BEGIN

// A binary BVH node that stores the boxes of both children, so one 64-byte fetch tests two boxes
// (the layout of Aila & Laine 2009). The w components carry integers as float bits:
//   leftMin.w  = left child reference,  leftMax.w  = left child primitive count
//   rightMin.w = right child reference, rightMax.w = right child primitive count
// A child with count == 0 is an inner node whose index (relative to its BVH's first node) is the reference;
// a child with count > 0 is a leaf covering primitives [reference, reference + count) of its BVH's
// leaf-ordered primitive array. A child with count == 0 and reference == 0 is empty (node 0 is the root
// and is never a child); this only occurs when the whole BVH holds a single leaf.
struct BvhNode {
    vec4 leftMin;
    vec4 leftMax;
    vec4 rightMin;
    vec4 rightMax;
};

// Deepest tree the builder produces per level; the traversal stack covers one TLAS and one BLAS path.
RIPPLE_CONST uint BVH_MAX_DEPTH = 48u;
// Largest leaf the builder makes; the kernels reserve this many steps before entering a leaf.
RIPPLE_CONST uint BVH_MAX_LEAF_SIZE = 8u;

RIPPLE_GPU_END
#endif
