// The surface at a closest hit: world position from the barycentrics (or the analytic shape) and the
// instance transform, geometric and shading normals facing the incoming ray, and the interpolated color
// and texcoord attributes. Needs the buffer views of pt_common.glsl.
#ifndef RIPPLE_SURFACE_GLSL
#define RIPPLE_SURFACE_GLSL
#include "features.glsl"
#include "primitive_refs.glsl"
#include "unstructured.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstanceShadingRef { InstanceShading instances[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer GeometriesRef { GeometryRecord geometries[]; };

// Gradient of the cell's trilinear interpolant at object-space point x (clamped into the cell): the
// iso-surface's normal direction, pointing to higher values.
vec3 isoCellGradient(IsoCellPrim cell, vec3 x) {
    if (hasFeature(FEATURE_MESH_ISOSURFACES) && (cell.meshLow | cell.meshHigh) != 0u) return meshIsoGradient(cell, x);
    vec3 w = clamp((x - cell.lowCorner.xyz) / cell.size.xyz, vec3(0.0), vec3(1.0));
    vec3 g = vec3(0.0);
    for (int n = 0; n < 8; ++n) {
        int i = n & 1, j = (n >> 1) & 1, l = n >> 2;
        float c = n < 4 ? cell.values0[n] : cell.values1[n - 4];
        vec3 f = vec3(i == 1 ? w.x : 1.0 - w.x, j == 1 ? w.y : 1.0 - w.y, l == 1 ? w.z : 1.0 - w.z);
        vec3 s = vec3(i == 1 ? 1.0 : -1.0, j == 1 ? 1.0 : -1.0, l == 1 ? 1.0 : -1.0);
        g += c * vec3(s.x * f.y * f.z, f.x * s.y * f.z, f.x * f.y * s.z);
    }
    return g / cell.size.xyz;
}

struct SurfacePoint {
    vec3 position;         // world space
    vec3 geometricNormal;  // unit, world space, facing the incoming ray
    vec3 shadingNormal;    // unit, world space, on the same side as geometricNormal
    bool hasColor;
    vec4 color;            // the color attribute (per vertex, interpolated, or per primitive)
    vec2 texcoord;         // (0, 0) where the geometry has none
    uint material;
    bool frontFace;        // the ray arrived on the side the object-space normal points to
    vec3 tangent;          // world space, along increasing texcoord u (normal maps); (0,0,0) where unknown
    float tangentSign;     // the bitangent is tangentSign * cross(shadingNormal, tangent)
    // Where samplers find the other attributes (sampler.glsl reads them only when a sampler asks).
    uint instance;         // index into SceneDesc.instanceShading (its uniform attributes)
    uint geometry;         // index into SceneDesc.geometries
    // Per-vertex attribute entries and their weights: a triangle's vertices and barycentrics; a cylinder's
    // or cone's two ends (entries 2p and 2p + 1 of its per-primitive pairs) and the axial fraction; a
    // sphere's own entry. Zero weights for iso-surfaces.
    uvec3 vertices;
    vec3 bary;
    uint primitiveId;      // as the application numbered its primitives (quads, not their triangles)
};

vec3 transformPoint(vec4 rows[3], vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec3(dot(rows[0], h), dot(rows[1], h), dot(rows[2], h));
}

// Object-space normal to world space: by the transpose of worldToObject (the inverse transpose of the
// instance transform), so normals stay perpendicular under non-uniform scale.
vec3 transformNormal(vec4 worldToObject[3], vec3 n) {
    return n.x * worldToObject[0].xyz + n.y * worldToObject[1].xyz + n.z * worldToObject[2].xyz;
}

vec3 safeNormalize(vec3 v, vec3 fallback) {
    float l2 = dot(v, v);
    return (l2 > 0.0 && !isinf(l2)) ? v * inversesqrt(l2) : fallback;
}

vec4 attributeAt(SceneDesc scene, uint offset, uint index) { return Vec4sRef(scene.attributes).values[offset + index]; }

vec4 interpolate(SceneDesc scene, uint offset, uvec3 idx, vec3 bary) {
    return bary.x * attributeAt(scene, offset, idx.x) + bary.y * attributeAt(scene, offset, idx.y) +
           bary.z * attributeAt(scene, offset, idx.z);
}

// A cone or curve segment at a ray point near its surface (hit.u: axial fraction, hit.v: 0 side, 1 flat
// cap, 2 end sphere): the point put back on the surface and the outward normal, both in object space.
void coneSurface(ConePrim cone, vec3 rayPoint, Hit hit, out vec3 point, out vec3 normal) {
    vec3 axis = cone.p1Radius.xyz - cone.p0Radius.xyz;
    float len = length(axis);
    vec3 w = axis / len;
    vec4 end = hit.u < 0.5 ? cone.p0Radius : cone.p1Radius;
    if (hit.v > 1.5) {  // the sphere at a round end
        normal = safeNormalize(rayPoint - end.xyz, hit.u < 0.5 ? -w : w);
        point = end.xyz + end.w * normal;
    } else if (hit.v > 0.5) {  // a flat cap
        normal = hit.u < 0.5 ? -w : w;
        point = rayPoint - dot(rayPoint - end.xyz, w) * w;
    } else {
        // The side leans by the radius change per unit length (for a round segment, the tangent cone's).
        float slope = (cone.p1Radius.w - cone.p0Radius.w) / len;
        if ((cone.flags & CONE_ROUND) != 0u) slope /= sqrt(max(1.0 - slope * slope, 1e-12));
        vec3 across = rayPoint - cone.p0Radius.xyz;
        across -= dot(across, w) * w;
        vec3 radial = safeNormalize(across, abs(w.x) < 0.9 ? normalize(cross(w, vec3(1.0, 0.0, 0.0))) : normalize(cross(w, vec3(0.0, 1.0, 0.0))));
        normal = normalize(radial - slope * w);
        point = rayPoint;
    }
}

// dp/du of a triangle from its texcoords, object space; (0,0,0) when the texcoords are degenerate.
vec3 triangleTangent(TrianglePrim tri, vec2 t0, vec2 t1, vec2 t2) {
    vec2 d1 = t1 - t0, d2 = t2 - t0;
    float det = d1.x * d2.y - d1.y * d2.x;
    if (abs(det) < 1e-20) return vec3(0.0);
    return ((tri.v1.xyz - tri.v0.xyz) * d2.y - (tri.v2.xyz - tri.v0.xyz) * d1.y) / det;
}

SurfacePoint surfaceAt(SceneDesc scene, Ray ray, Hit hit) {
    InstanceShading inst = InstanceShadingRef(scene.instanceShading).instances[hit.instanceId];
    GeometryRecord geom = GeometriesRef(scene.geometries).geometries[inst.geometry];
    uint slot = UintsRef(scene.primSlots).values[geom.slotOffset + hit.primId];
    SurfacePoint s;
    s.material = inst.material;
    s.instance = hit.instanceId;
    s.geometry = inst.geometry;
    s.vertices = uvec3(0u);
    s.bary = vec3(0.0);
    s.primitiveId = hit.primId / max(geom.trianglesPerPrimitive, 1u);
    s.hasColor = false;
    s.color = vec4(1.0);
    s.texcoord = vec2(0.0);
    vec3 objectTangent = vec3(0.0);
    s.tangentSign = 1.0;
    vec3 objectPoint = vec3(0.0);
    vec3 objectNormal = vec3(0.0, 0.0, 1.0);
    vec3 objectShadingNormal = objectNormal;
    if (hasFeature(FEATURE_TRIANGLES) && geom.kind == GEOMETRY_TRIANGLES) {
        TrianglePrim tri = TrianglesRef(scene.triangles).triangles[slot];
        vec3 bary = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
        objectPoint = bary.x * tri.v0.xyz + bary.y * tri.v1.xyz + bary.z * tri.v2.xyz;
        objectNormal = cross(tri.v1.xyz - tri.v0.xyz, tri.v2.xyz - tri.v0.xyz);
        objectShadingNormal = objectNormal;
        uvec3 idx = uvec3(3u * hit.primId) + uvec3(0u, 1u, 2u);
        if (geom.indexOffset != NO_ATTRIBUTE) {
            UintsRef indices = UintsRef(scene.vertexIndices);
            uint first = geom.indexOffset + 3u * hit.primId;
            idx = uvec3(indices.values[first], indices.values[first + 1u], indices.values[first + 2u]);
        }
        s.vertices = idx;
        s.bary = bary;
        if (geom.normalOffset != NO_ATTRIBUTE) objectShadingNormal = interpolate(scene, geom.normalOffset, idx, bary).xyz;
        if (geom.texcoordOffset != NO_ATTRIBUTE) {
            s.texcoord = interpolate(scene, geom.texcoordOffset, idx, bary).xy;
            objectTangent = triangleTangent(tri, attributeAt(scene, geom.texcoordOffset, idx.x).xy,
                                            attributeAt(scene, geom.texcoordOffset, idx.y).xy,
                                            attributeAt(scene, geom.texcoordOffset, idx.z).xy);
        }
        if (geom.tangentOffset != NO_ATTRIBUTE) {
            vec4 tangent = interpolate(scene, geom.tangentOffset, idx, bary);
            objectTangent = tangent.xyz;
            s.tangentSign = tangent.w < 0.0 ? -1.0 : 1.0;
        }
        if (geom.colorOffset != NO_ATTRIBUTE) {
            s.hasColor = true;
            s.color = interpolate(scene, geom.colorOffset, idx, bary);
        } else if (geom.primitiveColorOffset != NO_ATTRIBUTE) {
            s.hasColor = true;
            s.color = attributeAt(scene, geom.primitiveColorOffset, hit.primId);
        }
    } else if (hasFeature(FEATURE_ISOSURFACES) && geom.kind == GEOMETRY_ISOSURFACES) {
        // The hit point from the ray (the root is found to float precision); the normal from the gradient
        // of the cell's interpolant. Colour: one per isovalue.
        objectPoint = transformPoint(inst.worldToObject, ray.origin.xyz + hit.t * ray.direction.xyz);
        objectNormal = safeNormalize(isoCellGradient(IsoCellsRef(scene.isoCells).cells[slot], objectPoint), vec3(0.0, 0.0, 1.0));
        objectShadingNormal = objectNormal;
        s.primitiveId = uint(hit.u);  // the isovalue's index
        if (geom.colorOffset != NO_ATTRIBUTE) {
            s.hasColor = true;
            s.color = attributeAt(scene, geom.colorOffset, s.primitiveId);
        }
    } else if (hasFeature(FEATURE_SPHERES | FEATURE_CYLINDERS | FEATURE_CONES)) {
        // Analytic shapes: the hit point from the ray in object space, then put back on the surface.
        vec3 rayPoint = transformPoint(inst.worldToObject, ray.origin.xyz + hit.t * ray.direction.xyz);
        if (hasFeature(FEATURE_SPHERES) && geom.kind == GEOMETRY_SPHERES) {
            vec4 sphere = SpheresRef(scene.spheres).spheres[slot].centerRadius;
            objectNormal = safeNormalize(rayPoint - sphere.xyz, vec3(0.0, 0.0, 1.0));
            objectPoint = sphere.xyz + sphere.w * objectNormal;
            s.vertices = uvec3(hit.primId);
            s.bary = vec3(1.0, 0.0, 0.0);
        } else if (hasFeature(FEATURE_CONES) && geom.kind == GEOMETRY_CONES) {
            coneSurface(ConesRef(scene.cones).cones[slot], rayPoint, hit, objectPoint, objectNormal);
        } else if (hasFeature(FEATURE_CYLINDERS)) {
            CylinderPrim cyl = CylindersRef(scene.cylinders).cylinders[slot];
            vec3 axis = normalize(cyl.p1.xyz - cyl.p0Radius.xyz);
            vec3 onAxis = mix(cyl.p0Radius.xyz, cyl.p1.xyz, hit.u);
            if (hit.v > 0.5) {  // a cap
                objectNormal = hit.u < 0.5 ? -axis : axis;
                objectPoint = rayPoint - dot(rayPoint - onAxis, axis) * axis;
            } else {
                vec3 across = rayPoint - onAxis;
                across -= dot(across, axis) * axis;
                objectNormal = safeNormalize(across, vec3(0.0, 0.0, 1.0));
                objectPoint = onAxis + cyl.p0Radius.w * objectNormal;
            }
        }
        if (geom.kind != GEOMETRY_SPHERES) {
            // Both segment shapes report the axial fraction in hit.u (0 at the first end, 1 at the second); the
            // side of a round segment of changing radius reaches a little beyond [0, 1] before its end spheres
            // take over, and attributes stay within the end values there.
            float along = clamp(hit.u, 0.0, 1.0);
            s.vertices = uvec3(2u * hit.primId, 2u * hit.primId + 1u, 2u * hit.primId + 1u);
            s.bary = vec3(1.0 - along, along, 0.0);
        }
        objectShadingNormal = objectNormal;
        if (geom.colorOffset != NO_ATTRIBUTE) {
            s.hasColor = true;
            s.color = attributeAt(scene, geom.colorOffset, hit.primId);
        }
    }
    if ((inst.attributeMask & INSTANCE_ATTRIBUTE_COLOR) != 0u) {
        // The instance's uniform colour replaces the geometry's on this instance.
        s.hasColor = true;
        s.color = attributeAt(scene, inst.attributeOffset, 0u);
    }
    s.position = transformPoint(inst.objectToWorld, objectPoint);
    vec3 ng = safeNormalize(transformNormal(inst.worldToObject, objectNormal), -normalize(ray.direction.xyz));
    s.frontFace = dot(ng, ray.direction.xyz) <= 0.0;
    if (!s.frontFace) ng = -ng;
    s.tangent = transformPoint(inst.objectToWorld, objectTangent) - transformPoint(inst.objectToWorld, vec3(0.0));
    vec3 ns = safeNormalize(transformNormal(inst.worldToObject, objectShadingNormal), ng);
    if (dot(ns, ng) < 0.0) ns = -ns;
    s.geometricNormal = ng;
    s.shadingNormal = ns;
    return s;
}

#endif
