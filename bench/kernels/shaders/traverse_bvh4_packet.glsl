// Subgroup packet traversal of ripple-bench's single-level BVH4 (--traversal packet), shared by
// trace_{closest,any}_bvh4p.comp (full nodes) and trace_{closest,any}_bvh4qp.comp (compressed nodes).
// The lanes of a subgroup walk ONE stack together: each tests the node's four child boxes against its own
// ray (with its own closest t), and the subgroup descends into every child that any live lane enters,
// nearest first by the smallest entry distance over the lanes. Because the node is the same for all lanes,
// it is fetched cooperatively: lane i loads 16-byte block i % 4 of it (a full node's blocks 4-6 in a
// second load) and the blocks are broadcast, so on lavapipe (one lane per SIMD slot, every fetch a per-lane
// gather) a compressed node costs one load per lane instead of four (a full node two instead of seven).
// Triangles are fetched the same way.
// Every lane must reach every subgroup operation, so no lane leaves early: lanes past rayCount and any-hit
// lanes that found a hit ride along with +inf box distances, and the loop's condition is subgroup-uniform.
// The step budget (params.stepBudget) counts the packet's iterations; when it runs out every lane still
// searching is flagged HIT_FLAG_RAN_OUT, as in traverse_bvh4.glsl. Needs full subgroups of at least 4
// lanes: the host checks the size and that the workgroup size is a multiple of it, which lavapipe and
// desktop GPUs fill (the pipeline does not ask for VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_vote : require

#include "shared/ray.h"
#include "shared/scene.h"
#include "bvh4_node.glsl"

layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push { Bvh4TraceParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BlocksRef { uvec4 blocks[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };

#if BVH4_COMPRESSED
const uint NODE_BLOCKS = 4u;  // frame, quantX, quantZ, children
#else
const uint NODE_BLOCKS = 7u;  // minX, maxX, minY, maxY, minZ, maxZ, children
#endif
const uint TRIANGLE_BLOCKS = 3u;  // v0, v1, v2
// Lanes that share one item's load: the smallest subgroup served (lavapipe at LP_NATIVE_VECTOR_WIDTH=128).
const uint LOAD_LANES = 4u;

// This lane's block of item `item` (items of `blockCount` blocks from `base`) in load `part`: lane i loads
// block part * LOAD_LANES + i % LOAD_LANES. Lanes past the item's last block load that block again, which
// keeps every address inside the item.
uvec4 loadOwnBlock(uint64_t base, uint item, uint blockCount, uint part) {
    uint block = min(part * LOAD_LANES + gl_SubgroupInvocationID % LOAD_LANES, blockCount - 1u);
    return BlocksRef(base).blocks[item * blockCount + block];
}

BVH4_NODE loadNode(uint index) {
    uvec4 own = loadOwnBlock(params.nodes, index, NODE_BLOCKS, 0u);
    BVH4_NODE node;
#if BVH4_COMPRESSED
    node.frame = uintBitsToFloat(subgroupBroadcast(own, 0u));
    node.quantX = subgroupBroadcast(own, 1u);
    node.quantZ = subgroupBroadcast(own, 2u);
    node.children = subgroupBroadcast(own, 3u);
#else
    uvec4 ownHigh = loadOwnBlock(params.nodes, index, NODE_BLOCKS, 1u);
    node.minX = uintBitsToFloat(subgroupBroadcast(own, 0u));
    node.maxX = uintBitsToFloat(subgroupBroadcast(own, 1u));
    node.minY = uintBitsToFloat(subgroupBroadcast(own, 2u));
    node.maxY = uintBitsToFloat(subgroupBroadcast(own, 3u));
    node.minZ = uintBitsToFloat(subgroupBroadcast(ownHigh, 0u));
    node.maxZ = uintBitsToFloat(subgroupBroadcast(ownHigh, 1u));
    node.children = subgroupBroadcast(ownHigh, 2u);
#endif
    return node;
}

uint stack[BVH4_STACK_SIZE];
uint stackSize;
bool overflow;

void push(uint entry) {
    if (stackSize >= BVH4_STACK_SIZE) overflow = true;
    else stack[stackSize++] = entry;
}

// Entry distances of a live lane's ray into the four children, each the smallest over the subgroup (+inf:
// no live lane enters it). One vec4 reduction, not four: on lavapipe each reduction is a loop over lanes.
vec4 packetEnterChildren(BVH4_NODE node, bool live, vec3 origin, vec3 invDirection, float tmin, float tFar) {
    vec4 d = vec4(uintBitsToFloat(0x7f800000u));
    if (live) {
        d.x = bvh4EnterChild(node, 0u, origin, invDirection, tmin, tFar);
        d.y = bvh4EnterChild(node, 1u, origin, invDirection, tmin, tFar);
        d.z = bvh4EnterChild(node, 2u, origin, invDirection, tmin, tFar);
        d.w = bvh4EnterChild(node, 3u, origin, invDirection, tmin, tFar);
    }
    return subgroupMin(d);
}

void main() {
    uint rayIndex = gl_GlobalInvocationID.x;
    bool inRange = rayIndex < params.rayCount;
    bool live = inRange;  // still searching: a closest-hit lane until the end, an any-hit lane until a hit
    Ray ray = RaysRef(params.rays).rays[min(rayIndex, params.rayCount - 1u)];
    vec3 origin = ray.origin.xyz;
    vec3 direction = ray.direction.xyz;
    vec3 invDirection = safeReciprocal(direction);
    TriangleRay triRay = makeTriangleRay(origin, direction);
    float tmin = ray.origin.w;
    Hit best = Hit(ray.direction.w, 0.0, 0.0, 0u, 0xFFFFFFFFu, HIT_MISS);

    stackSize = 0u;
    overflow = false;
    if (params.nodeCount > 0u) push(0u);
    uint leafSlot = 0u;
    uint leafRemaining = 0u;
    uint steps = 0u;
    while (leafRemaining > 0u || stackSize > 0u) {
        if (++steps > params.stepBudget) {
            if (live) best.status |= HIT_FLAG_RAN_OUT;
            break;
        }
        if (leafRemaining == 0u) {
            uint entry = stack[--stackSize];
            if ((entry & BVH4_LEAF_BIT) == 0u) {
                BVH4_NODE node = loadNode(entry);
                vec4 d = packetEnterChildren(node, live, origin, invDirection, tmin, best.t);
                uvec4 c = node.children;
                bvh4SortNearestFirst(d, c);
                // Farthest first, so the nearest is popped next; children no lane enters sort last (+inf).
                if (!isinf(d.w)) push(c.w);
                if (!isinf(d.z)) push(c.z);
                if (!isinf(d.y)) push(c.y);
                if (!isinf(d.x)) push(c.x);
                if (overflow) {
                    if (live) best.status |= HIT_FLAG_STACK_OVERFLOW;
                    break;
                }
                continue;
            }
            // A leaf's first triangle is tested in the step that pops it: the lanes never diverge here, so
            // unlike traverse_bvh4.glsl no lane waits on another's node expansion.
            leafSlot = (entry >> 3) & BVH4_MAX_LEAF_FIRST;
            leafRemaining = (entry & 7u) + 1u;
        }
        uvec4 own = loadOwnBlock(params.triangles, leafSlot, TRIANGLE_BLOCKS, 0u);
        vec4 v0 = uintBitsToFloat(subgroupBroadcast(own, 0u));
        vec3 v1 = uintBitsToFloat(subgroupBroadcast(own, 1u).xyz);
        vec3 v2 = uintBitsToFloat(subgroupBroadcast(own, 2u).xyz);
        float t = best.t, u, v;
        if (live && intersectTriangle(triRay, v0.xyz, v1, v2, tmin, t, u, v))
            best = Hit(t, u, v, 0u, floatBitsToUint(v0.w), HIT_FOUND);
        ++leafSlot;
        --leafRemaining;
#if TRACE_ANY_HIT
        if (best.status == HIT_FOUND) live = false;  // any hit will do
        if (!subgroupAny(live)) break;
#endif
    }
    if (!inRange) return;
#if TRACE_ANY_HIT
    OcclusionRef(params.hits).occluded[rayIndex] = best.status;
#else
    HitsRef(params.hits).hits[rayIndex] = best;
#endif
}
