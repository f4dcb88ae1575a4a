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
#include "bvh4_node.glsl"

layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push { Bvh4TraceParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Nodes4Ref { BVH4_NODE nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TrianglesRef { TrianglePrim triangles[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };

uint stack[BVH4_STACK_SIZE];
uint stackSize;
bool overflow;

void push(uint entry) {
    if (stackSize >= BVH4_STACK_SIZE) overflow = true;
    else stack[stackSize++] = entry;
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
        uint child[4];
        uint entered = bvh4EnteredChildren(nodes.nodes[entry], origin, invDirection, tmin, best.t, child);
        // Farthest first, so the nearest is popped next (unrolled: a nested loop would count against the cap).
        if (entered > 3u) push(child[3]);
        if (entered > 2u) push(child[2]);
        if (entered > 1u) push(child[1]);
        if (entered > 0u) push(child[0]);
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
