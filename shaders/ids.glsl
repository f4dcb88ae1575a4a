// The id fields of a SurfaceRecord, filled by the rank that owns the hit (it alone has the instance and
// geometry tables). Needs pt_common.glsl, surface.glsl and features.glsl. Misses, and frames without an
// id channel, get ~0u.
#ifndef RIPPLE_IDS_GLSL
#define RIPPLE_IDS_GLSL

void writeSurfaceIds(inout SurfaceRecord r, Hit hit) {
    r.primitiveId = 0xFFFFFFFFu;
    r.objectId = 0xFFFFFFFFu;
    r.instanceId = 0xFFFFFFFFu;
    r.pad1 = 0u;
    const uint idChannels = FEATURE_CHANNEL_PRIMITIVE_ID | FEATURE_CHANNEL_OBJECT_ID | FEATURE_CHANNEL_INSTANCE_ID;
    if (!hasFeature(idChannels) || hit.status != HIT_FOUND) return;
    SceneDesc scene = SceneRef(params.scene).desc;
    InstanceShading inst = InstanceShadingRef(scene.instanceShading).instances[hit.instanceId];
    GeometryRecord geom = GeometriesRef(scene.geometries).geometries[inst.geometry];
    // Quads reach the kernels as two triangles each: the application numbered the quads.
    r.primitiveId = hit.primId / max(geom.trianglesPerPrimitive, 1u);
    // An iso-surface's primitives are the cells it crosses; the application numbered its isovalues.
    if (hasFeature(FEATURE_ISOSURFACES) && geom.kind == GEOMETRY_ISOSURFACES) r.primitiveId = uint(hit.u);
    r.objectId = inst.objectId;
    r.instanceId = inst.userInstanceId;
}

#endif
