// Ray-query traversal (VK_KHR_ray_query) of the scene's acceleration structures, shared by
// trace_closest_rq.comp (TRACE_ANY_HIT 0) and trace_any_rq.comp (1); the same rays in and hits out as the
// software kernels (traverse.glsl). Triangles are opaque, so the device commits them itself; spheres,
// cylinders and cones are AABB candidates confirmed here by intersect.glsl in object space. The TLAS
// custom index of an instance is its slot in SceneDesc.instances.
//
// lavapipe ends every loop of a shader silently once a per-invocation iteration budget is spent, and the
// device's own traversal inside rayQueryProceedEXT is such a loop. A traversal that stops with
// rayQueryProceedEXT still returning true (cut by that budget, or by RQ_MAX_PROCEEDS here) is flagged
// HIT_FLAG_RAN_OUT, never silently wrong.
#extension GL_EXT_ray_query : require

#include "trace_params.glsl"
#include "shared/scene.h"
#include "features.glsl"
#include "intersect.glsl"
#include "primitive_refs.glsl"

layout(local_size_x_id = 0) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneRef { SceneDesc desc; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstancesRef { InstancePrim instances[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RaysRef { Ray rays[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer HitsRef { Hit hits[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer OcclusionRef { uint occluded[]; };

// Most candidates one ray confirms or rejects. Each costs at least one iteration of the loop below and
// one of the device's traversal loop, so this stays well under lavapipe's budget (see above).
const uint RQ_MAX_PROCEEDS = 16000u;
const uint NO_INSTANCE = 0xFFFFFFFFu;

void writeResult(uint rayIndex, Hit best) {
#if TRACE_ANY_HIT
    OcclusionRef(params.hits).occluded[rayIndex] = best.status;
#else
    HitsRef(params.hits).hits[rayIndex] = best;
#endif
}

bool finiteVec(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
    uint rayIndex = gl_GlobalInvocationID.x;
    if (rayIndex >= traceRayCount()) return;
    Ray ray = RaysRef(params.rays).rays[rayIndex];
    float tmin = max(ray.origin.w, 0.0);
    float tmax = ray.direction.w;
    Hit best = Hit(tmax, 0.0, 0.0, NO_INSTANCE, NO_INSTANCE, HIT_MISS);
    SceneRef sceneRef = SceneRef(params.scene);
    uint64_t tlas = sceneRef.desc.accelerationStructure;
    // What the software kernels answer as misses, and what ray queries may not be given (NaN, tmax < tmin).
    if (tlas == 0ul || !(tmax > tmin) || !finiteVec(ray.origin.xyz) || !finiteVec(ray.direction.xyz) ||
        dot(ray.direction.xyz, ray.direction.xyz) == 0.0) {
        writeResult(rayIndex, best);
        return;
    }
    InstancesRef instances = InstancesRef(sceneRef.desc.instances);

    rayQueryEXT rq;
    uint flags = TRACE_ANY_HIT != 0 ? gl_RayFlagsTerminateOnFirstHitEXT : gl_RayFlagsNoneEXT;
    rayQueryInitializeEXT(rq, accelerationStructureEXT(tlas), flags, 0xFFu, ray.origin.xyz, tmin, ray.direction.xyz,
                          tmax);
    // The confirmed AABB hit committed last; it is the committed hit unless a nearer triangle followed.
    float aabbU = 0.0, aabbV = 0.0;
    uint aabbPrimId = 0u;
    bool finished = false;
    for (uint proceeds = 0u; proceeds < RQ_MAX_PROCEEDS; ++proceeds) {
        if (!rayQueryProceedEXT(rq)) {
            finished = true;
            break;
        }
        if (rayQueryGetIntersectionTypeEXT(rq, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
        uint slot = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, false));
        uint primSlot = instances.instances[slot].primOffset + uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false));
        uint kind = instances.instances[slot].geometryKind;
        vec3 origin = rayQueryGetIntersectionObjectRayOriginEXT(rq, false);
        vec3 direction = rayQueryGetIntersectionObjectRayDirectionEXT(rq, false);
        float t = rayQueryGetIntersectionTypeEXT(rq, true) == gl_RayQueryCommittedIntersectionNoneEXT
                      ? tmax : rayQueryGetIntersectionTEXT(rq, true);
        float u = 0.0, v = 0.0;
        bool hit = false;
        uint primId = 0u;
        if (hasFeature(FEATURE_SPHERES) && kind == GEOMETRY_SPHERES) {
            SpherePrim sphere = SpheresRef(sceneRef.desc.spheres).spheres[primSlot];
            hit = intersectSphere(origin, direction, sphere.centerRadius, tmin, t);
            primId = sphere.primId;
        } else if (hasFeature(FEATURE_CYLINDERS) && kind == GEOMETRY_CYLINDERS) {
            CylinderPrim cylinder = CylindersRef(sceneRef.desc.cylinders).cylinders[primSlot];
            hit = intersectCylinder(origin, direction, cylinder.p0Radius, cylinder.p1.xyz, cylinder.caps, tmin, t, u, v);
            primId = cylinder.primId;
        } else if (hasFeature(FEATURE_CONES) && kind == GEOMETRY_CONES) {
            ConePrim cone = ConesRef(sceneRef.desc.cones).cones[primSlot];
            hit = intersectCone(origin, direction, cone.p0Radius, cone.p1Radius, cone.flags, tmin, t, u, v);
            primId = cone.primId;
        } else if (hasFeature(FEATURE_ISOSURFACES) && kind == GEOMETRY_ISOSURFACES) {
            IsoCellPrim cell = IsoCellsRef(sceneRef.desc.isoCells).cells[primSlot];
            hit = intersectIsoCell(origin, direction, cell, tmin, t);
            primId = cell.primId;
            u = float(cell.isovalueIndex);
        }
        if (hit) {
            rayQueryGenerateIntersectionEXT(rq, t);
            aabbU = u;
            aabbV = v;
            aabbPrimId = primId;
            if (TRACE_ANY_HIT != 0) rayQueryTerminateEXT(rq);  // any hit will do
        }
    }

    uint committed = rayQueryGetIntersectionTypeEXT(rq, true);
    if (committed != gl_RayQueryCommittedIntersectionNoneEXT) {
        uint slot = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rq, true));
        best.t = rayQueryGetIntersectionTEXT(rq, true);
        best.instanceId = instances.instances[slot].instanceId;
        best.status = HIT_FOUND;
        if (committed == gl_RayQueryCommittedIntersectionTriangleEXT) {
            uint primSlot = instances.instances[slot].primOffset + uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, true));
            best.primId = floatBitsToUint(TrianglesRef(sceneRef.desc.triangles).triangles[primSlot].v0.w);
            vec2 barycentrics = rayQueryGetIntersectionBarycentricsEXT(rq, true);
            best.u = barycentrics.x;
            best.v = barycentrics.y;
        } else {
            best.primId = aabbPrimId;
            best.u = aabbU;
            best.v = aabbV;
        }
    }
    if (!finished) best.status |= HIT_FLAG_RAN_OUT;
    writeResult(rayIndex, best);
}
