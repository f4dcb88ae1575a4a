// Expansion of one 4-wide BVH node (shared/bvh4.h), shared by the renderer's two-level traversal
// (traverse.glsl) and ripple-bench's single-level kernel (traverse_bvh4.glsl): the four child box tests and
// the order in which the children are pushed. BVH4_COMPRESSED picks the node type (1: 8-bit child boxes).
#ifndef RIPPLE_BVH4_NODE_GLSL
#define RIPPLE_BVH4_NODE_GLSL
#include "shared/bvh4.h"
#include "intersect.glsl"

#if BVH4_COMPRESSED
#define BVH4_NODE Bvh4CompressedNode
#else
#define BVH4_NODE Bvh4Node
#endif

// Entry distance into child `slot`'s box, +inf when the ray misses it or the slot is empty.
float bvh4EnterChild(BVH4_NODE node, uint slot, vec3 origin, vec3 invDirection, float tmin, float tFar) {
    if (node.children[slot] == BVH4_EMPTY_CHILD) return uintBitsToFloat(0x7f800000u);
#if BVH4_COMPRESSED
    uint exponents = floatBitsToUint(node.frame.w);
    vec3 scale = uintBitsToFloat(uvec3(exponents & 0xFFu, (exponents >> 8) & 0xFFu, (exponents >> 16) & 0xFFu) << 23);
    uint shift = 8u * slot;
    vec3 qlo = vec3(uvec3(node.quantX.x, node.quantX.z, node.quantZ.x) >> shift & 0xFFu);
    vec3 qhi = vec3(uvec3(node.quantX.y, node.quantX.w, node.quantZ.y) >> shift & 0xFFu);
    // q * scale is exact (8 bits times a power of two): the one rounding is the sum, as on the host.
    vec3 lo = node.frame.xyz + qlo * scale;
    vec3 hi = node.frame.xyz + qhi * scale;
#else
    vec3 lo = vec3(node.minX[slot], node.minY[slot], node.minZ[slot]);
    vec3 hi = vec3(node.maxX[slot], node.maxY[slot], node.maxZ[slot]);
#endif
    return intersectBox(lo, hi, origin, invDirection, tmin, tFar);
}

// Orders two (distance, child) pairs nearest first; the five of a sorting network order all four.
void bvh4Order(inout float da, inout uint ca, inout float db, inout uint cb) {
    if (db < da) {
        float d = da; da = db; db = d;
        uint c = ca; ca = cb; cb = c;
    }
}

// Sorts a node's four (entry distance, child) pairs nearest first: the five comparators of a sorting
// network. Missed children (+inf) end up last, so the entered ones are a prefix.
void bvh4SortNearestFirst(inout vec4 d, inout uvec4 c) {
    float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
    uint c0 = c.x, c1 = c.y, c2 = c.z, c3 = c.w;
    bvh4Order(d0, c0, d1, c1);
    bvh4Order(d2, c2, d3, c3);
    bvh4Order(d0, c0, d2, c2);
    bvh4Order(d1, c1, d3, c3);
    bvh4Order(d1, c1, d2, c2);
    d = vec4(d0, d1, d2, d3);
    c = uvec4(c0, c1, c2, c3);
}

// The children of `node` the ray enters before tFar, nearest first in child[0..count): the caller pushes
// them in reverse so the nearest is popped next.
uint bvh4EnteredChildren(BVH4_NODE node, vec3 origin, vec3 invDirection, float tmin, float tFar, out uint child[4]) {
    vec4 d = vec4(bvh4EnterChild(node, 0u, origin, invDirection, tmin, tFar),
                  bvh4EnterChild(node, 1u, origin, invDirection, tmin, tFar),
                  bvh4EnterChild(node, 2u, origin, invDirection, tmin, tFar),
                  bvh4EnterChild(node, 3u, origin, invDirection, tmin, tFar));
    uvec4 c = node.children;
    bvh4SortNearestFirst(d, c);
    child[0] = c.x, child[1] = c.y, child[2] = c.z, child[3] = c.w;
    return uint(!isinf(d.x)) + uint(!isinf(d.y)) + uint(!isinf(d.z)) + uint(!isinf(d.w));
}
#endif
