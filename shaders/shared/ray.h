// Rays and hits as the trace kernels read and write them, and the state of a suspended traversal.
#ifndef RIPPLE_SHARED_RAY_H
#define RIPPLE_SHARED_RAY_H
#include "common.h"
#include "bvh.h"

RIPPLE_GPU_BEGIN

struct Ray {
    vec4 origin;     // w: tmin
    vec4 direction;  // w: tmax; need not be normalised, t is in units of this vector
};

// Hit.status and occlusion results: the low byte says what was found, the flags say when the answer
// could not be completed (never silently wrong: a ray with a flag set has no trustworthy answer).
RIPPLE_CONST uint HIT_MISS = 0u;
RIPPLE_CONST uint HIT_FOUND = 1u;
RIPPLE_CONST uint HIT_FLAG_RAN_OUT = 0x100u;        // step budget spent and no resume slot or round left
RIPPLE_CONST uint HIT_FLAG_STACK_OVERFLOW = 0x200u; // deeper than the traversal stack (builder bug)

struct Hit {
    float t;
    float u;  // triangles: barycentrics of v1 and v2; spheres: 0; cylinders, cones: axial fraction (0 at p0)
    float v;  // cylinders: 0 on the side, 1 on a cap; cones: the same, and 2 on the sphere at a round end
    uint instanceId;
    uint primId;
    uint status;
};

// Traversal stack depth (BVH4, shared/bvh4.h): expanding a node pops one entry and pushes at most four, so
// a BVH of depth D leaves at most 3(D - 1) + 1 entries; one TLAS path, the sentinel and one BLAS path
// need at most 3(Dt + Db) - 4 <= 6 BVH_MAX_DEPTH (collapsing never deepens a tree).
RIPPLE_CONST uint TRAVERSAL_STACK_SIZE = 6u * BVH_MAX_DEPTH;

// A traversal that spent its step budget: enough to continue exactly where it stopped.
struct TraversalState {
    uint rayIndex;
    uint stackSize;
    uint instanceSlot;  // TLAS-order instance being traversed, or ~0u while in the TLAS
    uint pad0;
    Hit best;           // closest hit so far (closest-hit) or the occlusion flag in status (any-hit)
    uint pad1;
    uint pad2;
    uint stack[TRAVERSAL_STACK_SIZE];
};

// Header of a resume pool: count of suspended traversals and the indirect dispatch that resumes them.
struct ResumeHeader {
    uint count;
    uint groupsX;
    uint groupsY;
    uint groupsZ;
};

// Everything one trace dispatch needs, passed as push constants.
struct TraceParams {
    uint64_t scene;       // SceneDesc
    uint64_t rays;        // Ray[rayCount]
    uint64_t hits;        // Hit[rayCount] (closest) or uint[rayCount] (any-hit)
    uint64_t resumeIn;    // ResumeHeader then TraversalState[]: the traversals to continue (0: fresh rays)
    uint64_t resumeOut;   // where traversals that run out of budget are parked
    uint64_t rayCountAddress; // nonzero: the ray count is the uint there, written by an earlier kernel
                              // (the dispatch is then indirect); 0: rayCount below
    uint rayCount;
    uint resumeCapacity;  // TraversalState slots in resumeOut
    uint stepBudget;      // node visits + primitive tests per invocation before suspending
    uint pad0;
};

RIPPLE_GPU_END
#endif
