// The flat GPU scene the trace and shading kernels read: primitives in BVH leaf order, instances, the
// shading data of each geometry, materials, textures and lights, and one descriptor of device addresses
// (so no descriptor binding limit caps the size of a scene).
#ifndef RIPPLE_SHARED_SCENE_H
#define RIPPLE_SHARED_SCENE_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint GEOMETRY_TRIANGLES = 0u;
RIPPLE_CONST uint GEOMETRY_SPHERES = 1u;
RIPPLE_CONST uint GEOMETRY_CYLINDERS = 2u;
RIPPLE_CONST uint GEOMETRY_CONES = 3u;     // cones, and curves of round linear segments
RIPPLE_CONST uint GEOMETRY_ISOSURFACES = 4u; // iso-surfaces of a structured-regular field

// Which ends of a cylinder or cone are closed by a flat disk (CylinderPrim.caps, ConePrim.flags).
RIPPLE_CONST uint CAP_FIRST = 1u;
RIPPLE_CONST uint CAP_SECOND = 2u;
// ConePrim.flags: a curve segment, a sphere at each end joined by the cone tangent to both (no caps).
RIPPLE_CONST uint CONE_ROUND = 4u;

// "This attribute is absent" in the offsets of GeometryRecord and InstanceShading.
RIPPLE_CONST uint NO_ATTRIBUTE = 0xFFFFFFFFu;

// How a geometry's attribute0..3 is stored (2 bits each in GeometryRecord.attributeRates). Per vertex:
// interpolated with SurfacePoint.vertices/.bary (a triangle's vertices; a cylinder's or cone's two ends,
// stored as a pair per primitive; a sphere's own entry). Per primitive: indexed by the primitive id the
// application numbered. Uniform: one entry for the whole geometry.
RIPPLE_CONST uint ATTRIBUTE_RATE_VERTEX = 0u;
RIPPLE_CONST uint ATTRIBUTE_RATE_PRIMITIVE = 1u;
RIPPLE_CONST uint ATTRIBUTE_RATE_UNIFORM = 2u;

// Bits of InstanceShading.attributeMask: which of the instance's uniform attributes are set (they replace
// the geometry's own). At attributeOffset: color, then attribute0..3, one vec4 each.
RIPPLE_CONST uint INSTANCE_ATTRIBUTE_COLOR = 1u;
RIPPLE_CONST uint INSTANCE_ATTRIBUTE_0 = 2u;  // attribute1..3: the next bits

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

// One round cylinder in leaf order, from p0 to p1; primId is its index in its cylinder set. A hit reports
// u = the axial fraction (0 at p0, 1 at p1) and v = 0 on the side, 1 on a cap.
struct CylinderPrim {
    vec4 p0Radius;   // xyz: first end, w: radius
    vec4 p1;         // xyz: second end
    uint primId;
    uint caps;       // CAP_FIRST | CAP_SECOND: which ends a flat disk closes
    uint pad0;
    uint pad1;
};

// One cone frustum (or curve segment) in leaf order, from p0 with radius r0 to p1 with radius r1; primId is
// its index in its cone set. A hit reports u = the axial fraction (0 at p0, 1 at p1) and v = 0 on the side,
// 1 on a flat cap, 2 on the sphere at an end of a round segment.
struct ConePrim {
    vec4 p0Radius;   // xyz: first end, w: its radius
    vec4 p1Radius;   // xyz: second end, w: its radius
    uint primId;
    uint flags;      // CAP_FIRST | CAP_SECOND, or CONE_ROUND
    uint pad0;
    uint pad1;
};

// One cell of a structured-regular field that an iso-surface passes through, in leaf order: the surface
// inside it is where the trilinear interpolant of its 8 corner values equals the isovalue. primId is its
// index among the geometry's (cell, isovalue) pairs. A hit reports u = isovalueIndex (the primitive id
// ANARI applications see) and v = 0.
// A cell of an unstructured mesh instead (mesh != 0): lowCorner and size are the cell's object-space box,
// values0 the mesh's grid scale (xyz) and the cell's leaf-order index (w, as bits), values1.xyz the mesh's
// lowest corner (grid space is (object - values1.xyz) * values0.xyz); the surface is where the cell's own
// interpolant equals the isovalue (shaders/unstructured.glsl).
struct IsoCellPrim {
    vec4 lowCorner;  // xyz: the cell's corner of lowest coordinates, object space; w: the isovalue
    vec4 size;       // xyz: the cell's edge lengths (the field's spacing); w: 0
    vec4 values0;    // corner values at (x, y, z) offsets 000, 100, 010, 110
    vec4 values1;    // 001, 101, 011, 111
    uint primId;
    uint isovalueIndex;
    uint meshLow;    // device address of an unstructured mesh's words (UnstructuredHeader), low and high
    uint meshHigh;   // words; 0: a structured cell
};

// One instance of a BLAS, in TLAS leaf order. Rays are moved into object space with worldToObject
// without renormalising the direction, so a hit's t is the same in both spaces.
struct InstancePrim {
    vec4 worldToObject[3];  // rows of the affine 3x4 matrix
    vec4 objectToWorld[3];  // rows
    uint blasNodeOffset;    // first node of this instance's BLAS in SceneDesc.nodes
    uint primOffset;        // first primitive of the BLAS in triangles[], spheres[], cylinders[], cones[] or isoCells[]
    uint geometryKind;      // GEOMETRY_*
    uint instanceId;        // the instance's index in SceneDescription::instances (what a Hit reports)
};

// What shading needs of an instance, indexed by Hit.instanceId (the input order; instances that were
// skipped keep a slot that no hit ever names).
struct InstanceShading {
    vec4 worldToObject[3];  // rows; its transpose maps object-space normals to world space
    vec4 objectToWorld[3];  // rows
    uint geometry;          // index into SceneDesc.geometries
    uint material;          // index into SceneDesc.materials (always valid: bad indices get the default)
    uint objectId;          // the application's ids, for the id channels
    uint userInstanceId;
    uint attributeOffset;   // into SceneDesc.attributes: color, attribute0..3; NO_ATTRIBUTE: none set
    uint attributeMask;     // INSTANCE_ATTRIBUTE_* bits
    uint pad0;
    uint pad1;
};

// Where a geometry's shading data lives. Primitive ids are the input numbering (as in Hit.primId);
// primSlots[slotOffset + primId] is that primitive's index in triangles[], spheres[] or cylinders[], so
// the kernels read positions from the trace primitives instead of a second copy. Attribute offsets index
// SceneDesc.attributes (one vec4 per entry) or are NO_ATTRIBUTE.
struct GeometryRecord {
    uint kind;              // GEOMETRY_*
    uint slotOffset;        // into SceneDesc.primSlots
    uint indexOffset;       // into SceneDesc.vertexIndices, 3 per triangle; NO_ATTRIBUTE: non-indexed or unused
    uint normalOffset;      // per vertex (triangles)
    uint colorOffset;       // per vertex (triangles) or per primitive (spheres, cylinders)
    uint texcoordOffset;    // per vertex (triangles): xy
    uint primitiveColorOffset; // per triangle
    uint trianglesPerPrimitive;
    uint attributeOffset[4];   // attribute0..3, stored as attributeRates says
    uint attributeRates;       // 2 bits per attribute: ATTRIBUTE_RATE_*
    uint tangentOffset;        // per vertex (triangles): xyz along increasing texcoord u, w the handedness (+-1)
    uint pad1;
    uint pad2;
};

// Everything the kernels need to find the scene. All BVHs live in one node array: the TLAS first, then
// each BLAS at its instance's blasNodeOffset.
struct SceneDesc {
    uint64_t nodes;           // Bvh4CompressedNode[] (shared/bvh4.h)
    uint64_t triangles;       // TrianglePrim[]
    uint64_t spheres;         // SpherePrim[]
    uint64_t cylinders;       // CylinderPrim[]
    uint64_t instances;       // InstancePrim[], TLAS leaf order
    uint64_t instanceShading; // InstanceShading[], input order
    uint64_t geometries;      // GeometryRecord[]
    uint64_t primSlots;       // uint[]
    uint64_t vertexIndices;   // uint[]
    uint64_t attributes;      // vec4[]
    uint64_t materials;       // MaterialRecord[] (shared/material.h)
    uint64_t textures;        // TextureRecord[]
    uint64_t texels;          // uint[]: RGBA8 texels one word each, RGBA32F four words each
    uint64_t lights;          // LightRecord[]
    uint instanceCount;       // 0 for an empty scene: every ray misses
    uint lightCount;
    uint materialCount;
    uint textureCount;
    uint64_t cones;           // ConePrim[]
    float originUnit;         // min(1, largest |coordinate| of the world): ray-origin offsets near 0 scale with it
    uint volumeCount;         // VolumeRecords in volumes
    float lightPowerTotal;    // sum of the lights' selection powers: an emissive triangle's pdf needs it
    uint testedLightCount;    // the first lights, which rays test themselves (quad, ring, hdri, disc sun)
    uint bsdfTables;          // first word of the BSDF energy tables in texels (core/scene/BsdfTables.h)
    int environmentLight;     // index of the hdri light, or -1
    uint64_t accelerationStructure; // the TLAS for ray-query traversal (accelerationStructureEXT); 0 when
                                    // the scene was built without one or has no instances
    uint64_t volumes;         // VolumeRecord[] (shared/volume.h)
    uint64_t volumeData;      // float[]: macrocell majorants and transfer-function tables (voxels: VolumeRecord.voxels)
    uint64_t isoCells;        // IsoCellPrim[]
};

RIPPLE_GPU_END
#endif
