// The flat GPU scene the traversal kernels read: primitives in BVH leaf order, instances, and one
// descriptor of device addresses (so no descriptor binding limit caps the size of a scene).
#ifndef RIPPLE_SHARED_SCENE_H
#define RIPPLE_SHARED_SCENE_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint GEOMETRY_TRIANGLES = 0u;
RIPPLE_CONST uint GEOMETRY_SPHERES = 1u;

// One triangle, stored by value in leaf order; v0.w holds the triangle's index in its mesh (float bits).
struct TrianglePrim {
    vec4 v0;
    vec4 v1;
    vec4 v2;
};

// One sphere in leaf order; primId is its index in its sphere set.
struct SpherePrim {
    vec4 centerRadius;
    uint primId;
    uint pad0;
    uint pad1;
    uint pad2;
};

// One instance of a BLAS, in TLAS leaf order. Rays are moved into object space with worldToObject
// without renormalising the direction, so a hit's t is the same in both spaces.
struct InstancePrim {
    vec4 worldToObject[3];  // rows of the affine 3x4 matrix
    vec4 objectToWorld[3];  // rows; for normals and hit points in later stages
    uint blasNodeOffset;    // first node of this instance's BLAS in SceneDesc.nodes
    uint primOffset;        // first primitive of the BLAS in triangles[] or spheres[]
    uint geometryKind;      // GEOMETRY_TRIANGLES or GEOMETRY_SPHERES
    uint instanceId;        // the index the application gave this instance
};

// Everything the kernels need to find the scene. All BVHs live in one node array: the TLAS first, then
// each BLAS at its instance's blasNodeOffset.
struct SceneDesc {
    uint64_t nodes;      // BvhNode[]
    uint64_t triangles;  // TrianglePrim[]
    uint64_t spheres;    // SpherePrim[]
    uint64_t instances;  // InstancePrim[]
    uint instanceCount;  // 0 for an empty scene: every ray misses
    uint pad0;
    uint pad1;
    uint pad2;
};

RIPPLE_GPU_END
#endif
