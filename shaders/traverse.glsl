// Two-level 4-wide BVH traversal (TLAS over instances, a BLAS per geometry; nodes as in shared/bvh4.h)
// shared by trace_closest.comp (TRACE_ANY_HIT 0) and trace_any.comp (1).
// One invocation traces one ray, in ONE flat loop whose every iteration does one unit of work (pop a
// stack entry, or test one primitive). lavapipe silently ends a shader's loops after 65,535 iterations,
// counted per SIMD vector over all nested loops including their exit tests; with a single loop that count
// is the longest lane's step count, which params.stepBudget bounds. A traversal that needs more parks its
// exact state (stack, instance, best hit) in a resume pool and an indirect dispatch continues it; with no
// slot or round left the result is flagged HIT_FLAG_RAN_OUT instead of being silently wrong.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/ray.h"
#include "shared/scene.h"
#include "bvh4_node.glsl"
#include "features.glsl"
#include "trace_params.glsl"
#include "primitive_refs.glsl"

layout(local_size_x_id = 0) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneRef { SceneDesc desc; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer NodesRef { BVH4_NODE nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstancesRef { InstancePrim instances[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ResumeRef {
    ResumeHeader header;
    TraversalState states[];
};

// Stack entries are BVH4 child words of the BVH being traversed: an inner node, or a leaf (BVH4_LEAF_BIT),
// which in the TLAS is one instance (its first slot) and in a BLAS a run of primitives; plus the sentinel
// that returns from a BLAS to the TLAS, the word of an empty slot, which is never pushed as a child.
const uint ENTRY_LEAVE_BLAS = BVH4_EMPTY_CHILD;
const uint NO_INSTANCE = 0xFFFFFFFFu;

uint stack[TRAVERSAL_STACK_SIZE];
uint stackSize;
bool overflow;  // a push found the stack full: the answer is flagged, never silently wrong
uint instanceSlot;
Hit best;

// The scene addresses traversal reads (the rest of SceneDesc is for shading).
uint64_t sceneInstances;
uint64_t sceneTriangles;
uint64_t sceneSpheres;
uint64_t sceneCylinders;
uint64_t sceneCones;
uint64_t sceneIsoCells;

// The ray in the space of the BVH being traversed (world for the TLAS, object for a BLAS).
InstancePrim instance;
vec3 origin;
vec3 direction;
vec3 invDirection;
TriangleRay triRay;
float tmin;

void writeResult(uint rayIndex) {
#if TRACE_ANY_HIT
    OcclusionRef(params.hits).occluded[rayIndex] = best.status;
#else
    HitsRef(params.hits).hits[rayIndex] = best;
#endif
}

void push(uint entry) {
    if (stackSize >= TRAVERSAL_STACK_SIZE) overflow = true;
    else stack[stackSize++] = entry;
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

void enterSpace(Ray worldRay) {
    if (instanceSlot == NO_INSTANCE) {
        origin = worldRay.origin.xyz;
        direction = worldRay.direction.xyz;
    } else {
        instance = InstancesRef(sceneInstances).instances[instanceSlot];
        mat3x4 toObject = mat3x4(instance.worldToObject[0], instance.worldToObject[1], instance.worldToObject[2]);
        origin = vec4(worldRay.origin.xyz, 1.0) * toObject;
        direction = vec4(worldRay.direction.xyz, 0.0) * toObject;
    }
    invDirection = safeReciprocal(direction);
    if (hasFeature(FEATURE_TRIANGLES)) triRay = makeTriangleRay(origin, direction);
}

// Each kind's test is behind its feature bit, so a pipeline specialised for a scene holds only the tests
// of the kinds it has.
void testPrimitive(uint primSlot) {
    float t = best.t;
    float u = 0.0, v = 0.0;
    bool hit = false;
    uint primId = 0u;
    if (hasFeature(FEATURE_TRIANGLES) && instance.geometryKind == GEOMETRY_TRIANGLES) {
        TrianglePrim tri = TrianglesRef(sceneTriangles).triangles[primSlot];
        hit = intersectTriangle(triRay, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, t, u, v);
        primId = floatBitsToUint(tri.v0.w);
    } else if (hasFeature(FEATURE_SPHERES) && instance.geometryKind == GEOMETRY_SPHERES) {
        SpherePrim sphere = SpheresRef(sceneSpheres).spheres[primSlot];
        hit = intersectSphere(origin, direction, sphere.centerRadius, tmin, t);
        primId = sphere.primId;
    } else if (hasFeature(FEATURE_CYLINDERS) && instance.geometryKind == GEOMETRY_CYLINDERS) {
        CylinderPrim cylinder = CylindersRef(sceneCylinders).cylinders[primSlot];
        hit = intersectCylinder(origin, direction, cylinder.p0Radius, cylinder.p1.xyz, cylinder.caps, tmin, t, u, v);
        primId = cylinder.primId;
    } else if (hasFeature(FEATURE_CONES) && instance.geometryKind == GEOMETRY_CONES) {
        ConePrim cone = ConesRef(sceneCones).cones[primSlot];
        hit = intersectCone(origin, direction, cone.p0Radius, cone.p1Radius, cone.flags, tmin, t, u, v);
        primId = cone.primId;
    } else if (hasFeature(FEATURE_ISOSURFACES) && instance.geometryKind == GEOMETRY_ISOSURFACES) {
        IsoCellPrim cell = IsoCellsRef(sceneIsoCells).cells[primSlot];
        hit = intersectIsoCell(origin, direction, cell, tmin, t);
        primId = cell.primId;
        u = float(cell.isovalueIndex);
    }
    if (hit) best = Hit(t, u, v, instance.instanceId, primId, HIT_FOUND);
}

void main() {
    uint rayIndex;
    stackSize = 0u;
    overflow = false;
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
        if (rayIndex >= traceRayCount()) return;
        instanceSlot = NO_INSTANCE;
        best = Hit(RaysRef(params.rays).rays[rayIndex].direction.w, 0.0, 0.0, NO_INSTANCE, NO_INSTANCE, HIT_MISS);
        // A TLAS of one instance is a root with one leaf: the traversal starts in that instance's BLAS
        // (its root box stands in for the instance's), saving two steps per ray.
        uint instanceCount = SceneRef(params.scene).desc.instanceCount;
        if (instanceCount == 1u) instanceSlot = 0u;
        if (instanceCount > 0u) stack[stackSize++] = 0u;
    }

    SceneRef sceneRef = SceneRef(params.scene);
    sceneInstances = sceneRef.desc.instances;
    sceneTriangles = sceneRef.desc.triangles;
    sceneSpheres = sceneRef.desc.spheres;
    sceneCylinders = sceneRef.desc.cylinders;
    sceneCones = sceneRef.desc.cones;
    sceneIsoCells = sceneRef.desc.isoCells;
    NodesRef nodes = NodesRef(sceneRef.desc.nodes);
    Ray worldRay = RaysRef(params.rays).rays[rayIndex];
    tmin = worldRay.origin.w;
    enterSpace(worldRay);
    uint nodeBase = instanceSlot == NO_INSTANCE ? 0u : instance.blasNodeOffset;

    uint leafFirst = 0u;      // primitives of the leaf being tested, relative to the BLAS
    uint leafRemaining = 0u;
    // The entry to take next, held here instead of pushed and popped at once (the stack is per-lane
    // memory: each push and pop is a scatter or gather across the SIMD lanes).
    uint nextEntry = 0u;
    bool hasNext = false;
    // Loop iterations so far, counting the resume copy above and reserving the park copy below.
    uint steps = stackSize + TRAVERSAL_STACK_SIZE + 2u;
    bool budgetSpent = false;
    while (leafRemaining > 0u || hasNext || stackSize > 0u) {
        // Parking happens after the loop: its copy loop and atomics inside this one cost lavapipe 8-15% of
        // the traversal time even when no lane parks (measured with ripple-bench).
        if (++steps > params.stepBudget) {
            budgetSpent = true;
            break;
        }

        if (leafRemaining > 0u) {
            testPrimitive(instance.primOffset + leafFirst);
            ++leafFirst;
            --leafRemaining;
            if (TRACE_ANY_HIT != 0 && best.status == HIT_FOUND) break;  // any hit will do
            continue;
        }

        uint entry;
        if (hasNext) {
            entry = nextEntry;
            hasNext = false;
        } else {
            entry = stack[--stackSize];
        }
        if (entry == ENTRY_LEAVE_BLAS) {
            instanceSlot = NO_INSTANCE;
            nodeBase = 0u;
            enterSpace(worldRay);
        } else if ((entry & BVH4_LEAF_BIT) != 0u && instanceSlot == NO_INSTANCE) {
            instanceSlot = (entry >> 3) & BVH4_MAX_LEAF_FIRST;  // TLAS leaves hold one instance
            enterSpace(worldRay);
            nodeBase = instance.blasNodeOffset;
            // With nothing left in the TLAS the traversal ends with the BLAS: no way back is needed.
            if (stackSize > 0u) push(ENTRY_LEAVE_BLAS);
            nextEntry = 0u;
            hasNext = true;
        } else if ((entry & BVH4_LEAF_BIT) != 0u) {
            leafFirst = (entry >> 3) & BVH4_MAX_LEAF_FIRST;
            leafRemaining = (entry & 7u) + 1u;
        } else {
            uint child[4];
            uint entered = bvh4EnteredChildren(nodes.nodes[nodeBase + entry], origin, invDirection, tmin, best.t, child);
            // Farthest first, so the nearer are popped first (unrolled: a nested loop would count against
            // the cap); the nearest is taken next.
            if (entered > 3u) push(child[3]);
            if (entered > 2u) push(child[2]);
            if (entered > 1u) push(child[1]);
            nextEntry = child[0];
            hasNext = entered > 0u;
        }
        if (overflow) break;
    }
    if (budgetSpent && hasNext) push(nextEntry);
    if (budgetSpent && leafRemaining > 0u) push(BVH4_LEAF_BIT | leafFirst << 3 | (leafRemaining - 1u));
    if (overflow) best.status |= HIT_FLAG_STACK_OVERFLOW;
    else if (budgetSpent && park(rayIndex)) return;
    else if (budgetSpent) best.status |= HIT_FLAG_RAN_OUT;
    writeResult(rayIndex);
}
