// Two-level BVH traversal shared by trace_closest.comp (TRACE_ANY_HIT 0) and trace_any.comp (1).
// One invocation traces one ray. Every loop is bounded by params.stepBudget: lavapipe silently ends an
// invocation after 65,535 loop iterations, so a traversal that needs more parks its exact state (stack,
// instance, best hit) in a resume pool and an indirect dispatch continues it; with no slot or round left
// the result is flagged HIT_FLAG_RAN_OUT instead of being silently wrong.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/ray.h"
#include "shared/scene.h"
#include "intersect.glsl"

layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push { TraceParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneRef { SceneDesc desc; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer NodesRef { BvhNode nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TrianglesRef { TrianglePrim triangles[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SpheresRef { SpherePrim spheres[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstancesRef { InstancePrim instances[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ResumeRef {
    ResumeHeader header;
    TraversalState states[];
};

// Stack entries: a node index of the BVH being traversed, an instance to enter (TLAS leaves), or the
// sentinel that marks the return from a BLAS to the TLAS.
const uint ENTRY_INSTANCE = 0x80000000u;
const uint ENTRY_LEAVE_BLAS = 0xFFFFFFFFu;
const uint NO_INSTANCE = 0xFFFFFFFFu;

uint stack[TRAVERSAL_STACK_SIZE];
uint stackSize;
uint instanceSlot;
Hit best;

void writeResult(uint rayIndex) {
#if TRACE_ANY_HIT
    OcclusionRef(params.hits).occluded[rayIndex] = best.status;
#else
    HitsRef(params.hits).hits[rayIndex] = best;
#endif
}

// Parks the traversal for the next round; false when there is no round or slot left.
bool park(uint rayIndex) {
    if (params.resumeOut == 0ul) return false;
    ResumeRef pool = ResumeRef(params.resumeOut);
    uint slot = atomicAdd(pool.header.count, 1u);
    if (slot >= params.resumeCapacity) return false;
    atomicMax(pool.header.groupsX, slot / gl_WorkGroupSize.x + 1u);
    pool.states[slot].rayIndex = rayIndex;
    pool.states[slot].stackSize = stackSize;
    pool.states[slot].instanceSlot = instanceSlot;
    pool.states[slot].best = best;
    for (uint i = 0u; i < stackSize; ++i) pool.states[slot].stack[i] = stack[i];
    return true;
}

bool push(uint entry) {
    if (stackSize >= TRAVERSAL_STACK_SIZE) return false;
    stack[stackSize++] = entry;
    return true;
}

void main() {
    uint rayIndex;
    if (params.resumeIn != 0ul) {
        ResumeRef pool = ResumeRef(params.resumeIn);
        uint slot = gl_GlobalInvocationID.x;
        if (slot >= min(pool.header.count, params.resumeCapacity)) return;
        rayIndex = pool.states[slot].rayIndex;
        stackSize = pool.states[slot].stackSize;
        instanceSlot = pool.states[slot].instanceSlot;
        best = pool.states[slot].best;
        for (uint i = 0u; i < stackSize; ++i) stack[i] = pool.states[slot].stack[i];
    } else {
        rayIndex = gl_GlobalInvocationID.x;
        if (rayIndex >= params.rayCount) return;
        stackSize = 0u;
        instanceSlot = NO_INSTANCE;
        best = Hit(RaysRef(params.rays).rays[rayIndex].direction.w, 0.0, 0.0, NO_INSTANCE, NO_INSTANCE, HIT_MISS);
        if (SceneRef(params.scene).desc.instanceCount > 0u) push(0u);
    }

    SceneDesc scene = SceneRef(params.scene).desc;
    NodesRef nodes = NodesRef(scene.nodes);
    Ray worldRay = RaysRef(params.rays).rays[rayIndex];
    float tmin = worldRay.origin.w;

    // The ray in the space of the BVH being traversed (world for the TLAS, object for a BLAS).
    vec3 origin = worldRay.origin.xyz;
    vec3 direction = worldRay.direction.xyz;
    InstancePrim instance;
    uint nodeBase = 0u;
    if (instanceSlot != NO_INSTANCE) {
        instance = InstancesRef(scene.instances).instances[instanceSlot];
        origin = vec4(worldRay.origin.xyz, 1.0) * mat3x4(instance.worldToObject[0], instance.worldToObject[1], instance.worldToObject[2]);
        direction = vec4(worldRay.direction.xyz, 0.0) * mat3x4(instance.worldToObject[0], instance.worldToObject[1], instance.worldToObject[2]);
        nodeBase = instance.blasNodeOffset;
    }
    vec3 invDirection = safeReciprocal(direction);
    TriangleRay triRay = makeTriangleRay(origin, direction);

    uint steps = 0u;
    while (stackSize > 0u) {
        // Reserve enough for one node and two full leaves before committing to another iteration.
        if (steps + 2u * BVH_MAX_LEAF_SIZE + 1u > params.stepBudget) {
            if (!park(rayIndex)) {
                best.status |= HIT_FLAG_RAN_OUT;
                writeResult(rayIndex);
            }
            return;
        }
        ++steps;
        uint entry = stack[--stackSize];

        if (entry == ENTRY_LEAVE_BLAS) {
            instanceSlot = NO_INSTANCE;
            nodeBase = 0u;
            origin = worldRay.origin.xyz;
            direction = worldRay.direction.xyz;
            invDirection = safeReciprocal(direction);
            triRay = makeTriangleRay(origin, direction);
            continue;
        }
        if ((entry & ENTRY_INSTANCE) != 0u) {
            instanceSlot = entry & ~ENTRY_INSTANCE;
            instance = InstancesRef(scene.instances).instances[instanceSlot];
            mat3x4 toObject = mat3x4(instance.worldToObject[0], instance.worldToObject[1], instance.worldToObject[2]);
            origin = vec4(worldRay.origin.xyz, 1.0) * toObject;
            direction = vec4(worldRay.direction.xyz, 0.0) * toObject;
            invDirection = safeReciprocal(direction);
            triRay = makeTriangleRay(origin, direction);
            nodeBase = instance.blasNodeOffset;
            if (!push(ENTRY_LEAVE_BLAS) || !push(0u)) { best.status |= HIT_FLAG_STACK_OVERFLOW; break; }
            continue;
        }

        BvhNode node = nodes.nodes[nodeBase + entry];
        uint refs[2] = uint[2](floatBitsToUint(node.leftMin.w), floatBitsToUint(node.rightMin.w));
        uint counts[2] = uint[2](floatBitsToUint(node.leftMax.w), floatBitsToUint(node.rightMax.w));
        float tFar = best.t;
        float enter[2];
        enter[0] = (counts[0] == 0u && refs[0] == 0u) ? uintBitsToFloat(0x7f800000u)
                   : intersectBox(node.leftMin.xyz, node.leftMax.xyz, origin, invDirection, tmin, tFar);
        enter[1] = (counts[1] == 0u && refs[1] == 0u) ? uintBitsToFloat(0x7f800000u)
                   : intersectBox(node.rightMin.xyz, node.rightMax.xyz, origin, invDirection, tmin, tFar);
        // Visit the nearer child first: push it last.
        uint first = enter[1] < enter[0] ? 1u : 0u;
        bool overflow = false;
        for (uint n = 0u; n < 2u; ++n) {
            uint c = n == 0u ? 1u - first : first;  // far child, then near child
            if (isinf(enter[c])) continue;
            if (counts[c] == 0u) {
                overflow = overflow || !push(refs[c]);
            } else if (instanceSlot == NO_INSTANCE) {
                // TLAS leaf: defer each instance (leaves hold one instance; more work too).
                for (uint i = 0u; i < counts[c] && i < BVH_MAX_LEAF_SIZE; ++i)
                    overflow = overflow || !push(ENTRY_INSTANCE | (refs[c] + i));
            } else {
                // BLAS leaf: test its primitives now.
                steps += counts[c];
                for (uint i = 0u; i < counts[c] && i < BVH_MAX_LEAF_SIZE; ++i) {
                    uint primSlot = instance.primOffset + refs[c] + i;
                    float u, v;
                    bool hit;
                    uint primId;
                    float t = best.t;
                    if (instance.geometryKind == GEOMETRY_TRIANGLES) {
                        TrianglePrim tri = TrianglesRef(scene.triangles).triangles[primSlot];
                        hit = intersectTriangle(triRay, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, t, u, v);
                        primId = floatBitsToUint(tri.v0.w);
                    } else {
                        SpherePrim sphere = SpheresRef(scene.spheres).spheres[primSlot];
                        hit = intersectSphere(origin, direction, sphere.centerRadius, tmin, t);
                        u = 0.0;
                        v = 0.0;
                        primId = sphere.primId;
                    }
                    if (hit) {
                        best = Hit(t, u, v, instance.instanceId, primId, HIT_FOUND);
                        if (TRACE_ANY_HIT != 0) break;
                    }
                }
            }
            if (TRACE_ANY_HIT != 0 && best.status == HIT_FOUND) break;
        }
        if (TRACE_ANY_HIT != 0 && best.status == HIT_FOUND) break;  // any hit will do
        if (overflow) { best.status |= HIT_FLAG_STACK_OVERFLOW; break; }
    }
    writeResult(rayIndex);
}
