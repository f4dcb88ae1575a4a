// Single-level 4-wide BVH traversal over one triangle mesh (shaders/shared/bvh4.h), shared by
// trace_closest_bvh4.comp (TRACE_ANY_HIT 0) and trace_any_bvh4.comp (1): ripple-bench's --bvh-width 4;
// with BVH4_COMPRESSED 1 (trace_*_bvh4q.comp) the nodes are Bvh4CompressedNode (--nodes compressed).
// Like traverse.glsl it is ONE flat loop doing one unit of work per iteration (expand a node, or test one
// triangle), because lavapipe silently ends loops past its iteration cap; the count is bounded by
// params.stepBudget. There is no resume pool here: a ray that spends its budget is flagged
// HIT_FLAG_RAN_OUT (never silently wrong), which the agreement check counts as a disagreement.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/ray.h"
#include "shared/scene.h"
#include "shared/bvh4.h"
#include "intersect.glsl"

layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push { Bvh4TraceParams params; };

#if BVH4_COMPRESSED
#define NODE Bvh4CompressedNode
#else
#define NODE Bvh4Node
#endif
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Nodes4Ref { NODE nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TrianglesRef { TrianglePrim triangles[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };

#define INFINITY uintBitsToFloat(0x7f800000u)

uint stack[BVH4_STACK_SIZE];
uint stackSize;
bool overflow;

void push(uint entry) {
    if (stackSize >= BVH4_STACK_SIZE) overflow = true;
    else stack[stackSize++] = entry;
}

// Orders two (distance, child) pairs nearest first; the five of a sorting network order all four.
void order(inout float da, inout uint ca, inout float db, inout uint cb) {
    if (db < da) {
        float d = da; da = db; db = d;
        uint c = ca; ca = cb; cb = c;
    }
}

// Entry distance into child `slot`'s box, +inf when the ray misses it or the slot is empty.
float enterChild(NODE node, uint slot, vec3 origin, vec3 invDirection, float tmin, float tFar) {
    if (node.children[slot] == BVH4_EMPTY_CHILD) return INFINITY;
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

void main() {
    uint rayIndex = gl_GlobalInvocationID.x;
    if (rayIndex >= params.rayCount) return;
    Ray ray = RaysRef(params.rays).rays[rayIndex];
    vec3 origin = ray.origin.xyz;
    vec3 direction = ray.direction.xyz;
    vec3 invDirection = safeReciprocal(direction);
    TriangleRay triRay = makeTriangleRay(origin, direction);
    float tmin = ray.origin.w;
    Hit best = Hit(ray.direction.w, 0.0, 0.0, 0u, 0xFFFFFFFFu, HIT_MISS);
    Nodes4Ref nodes = Nodes4Ref(params.nodes);
    TrianglesRef triangles = TrianglesRef(params.triangles);

    stackSize = 0u;
    overflow = false;
    if (params.nodeCount > 0u) push(0u);
    uint leafSlot = 0u;
    uint leafRemaining = 0u;
    uint steps = 0u;
    while (leafRemaining > 0u || stackSize > 0u) {
        if (++steps > params.stepBudget) {
            best.status |= HIT_FLAG_RAN_OUT;
            break;
        }
        if (leafRemaining > 0u) {
            TrianglePrim tri = triangles.triangles[leafSlot];
            float t = best.t, u, v;
            if (intersectTriangle(triRay, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, t, u, v))
                best = Hit(t, u, v, 0u, floatBitsToUint(tri.v0.w), HIT_FOUND);
            ++leafSlot;
            --leafRemaining;
            if (TRACE_ANY_HIT != 0 && best.status == HIT_FOUND) break;  // any hit will do
            continue;
        }

        uint entry = stack[--stackSize];
        if ((entry & BVH4_LEAF_BIT) != 0u) {
            leafSlot = (entry >> 3) & BVH4_MAX_LEAF_FIRST;
            leafRemaining = (entry & 7u) + 1u;
            continue;
        }
        NODE node = nodes.nodes[entry];
        uvec4 child = node.children;
        float d0 = enterChild(node, 0u, origin, invDirection, tmin, best.t);
        float d1 = enterChild(node, 1u, origin, invDirection, tmin, best.t);
        float d2 = enterChild(node, 2u, origin, invDirection, tmin, best.t);
        float d3 = enterChild(node, 3u, origin, invDirection, tmin, best.t);
        uint c0 = child.x, c1 = child.y, c2 = child.z, c3 = child.w;
        order(d0, c0, d1, c1);
        order(d2, c2, d3, c3);
        order(d0, c0, d2, c2);
        order(d1, c1, d3, c3);
        order(d1, c1, d2, c2);
        // Farthest first, so the nearest is popped next.
        if (!isinf(d3)) push(c3);
        if (!isinf(d2)) push(c2);
        if (!isinf(d1)) push(c1);
        if (!isinf(d0)) push(c0);
        if (overflow) {
            best.status |= HIT_FLAG_STACK_OVERFLOW;
            break;
        }
    }
#if TRACE_ANY_HIT
    OcclusionRef(params.hits).occluded[rayIndex] = best.status;
#else
    HitsRef(params.hits).hits[rayIndex] = best;
#endif
}
