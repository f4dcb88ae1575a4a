// Unstructured meshes (shared/volume.h UnstructuredHeader, packed by core/scene/UnstructuredGrid.cpp): the
// field at a point, found by descending the BVH over the cells to the cells whose boxes hold the point and
// solving each one's map from its parametric space for the point. Tetrahedra: barycentric coordinates,
// exact. Hexahedra (trilinear), wedges (linear triangle times linear) and pyramids (bilinear base collapsing
// linearly to the apex): Newton's method on the map itself, so curved (non-planar) faces are where the
// interpolant puts them, and a point is inside when its parametric coordinates are in the reference cell and
// the map reproduces it. The value is the shape functions' blend of the corner values, or the cell's own
// value when the field is cell-centred (piecewise constant).
#ifndef RIPPLE_UNSTRUCTURED_GLSL
#define RIPPLE_UNSTRUCTURED_GLSL

#include "cubic.glsl"
#include "shared/bvh.h"
#include "shared/scene.h"
#include "shared/volume.h"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer MeshWordsRef { uint words[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MeshNodesRef { BvhNode nodes[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MeshVerticesRef { vec4 vertices[]; };

// Parametric tolerance of the inside test (so that points on a shared face are in both cells), and the
// Newton iterations a hexahedron, wedge or pyramid may take.
const float UNSTRUCTURED_INSIDE_EPSILON = 1e-5;
const uint UNSTRUCTURED_NEWTON_STEPS = 16u;
// Cells a walk from a known cell may test before the point query falls back to the BVH.
const uint UNSTRUCTURED_WALK_STEPS = 8u;

// Vertex `vertex`: its grid-space position and its value.
vec4 meshVertex(uint64_t mesh, UnstructuredHeader h, uint vertex) {
    return MeshVerticesRef(mesh + 4ul * uint64_t(h.vertexOffset)).vertices[vertex];
}

// Shape functions of a hexahedron, wedge or pyramid at parametric point q, with their gradients.
void shapeFunctions(uint shape, vec3 q, out float n[8], out vec3 dn[8]) {
    float r = q.x, s = q.y, t = q.z;
    for (int k = 0; k < 8; ++k) {
        n[k] = 0.0;
        dn[k] = vec3(0.0);
    }
    if (shape == UNSTRUCTURED_WEDGE) {
        float u = 1.0 - r - s;
        n[0] = u * (1.0 - t); n[1] = r * (1.0 - t); n[2] = s * (1.0 - t);
        n[3] = u * t;         n[4] = r * t;         n[5] = s * t;
        dn[0] = vec3(-(1.0 - t), -(1.0 - t), -u); dn[1] = vec3(1.0 - t, 0.0, -r); dn[2] = vec3(0.0, 1.0 - t, -s);
        dn[3] = vec3(-t, -t, u);                  dn[4] = vec3(t, 0.0, r);        dn[5] = vec3(0.0, t, s);
        return;
    }
    // The bilinear base (of the bottom face, and for a hexahedron also of the top).
    float b[4] = float[4]((1.0 - r) * (1.0 - s), r * (1.0 - s), r * s, (1.0 - r) * s);
    vec2 db[4] = vec2[4](vec2(-(1.0 - s), -(1.0 - r)), vec2(1.0 - s, -r), vec2(s, r), vec2(-s, 1.0 - r));
    for (int k = 0; k < 4; ++k) {
        n[k] = b[k] * (1.0 - t);
        dn[k] = vec3(db[k] * (1.0 - t), -b[k]);
        if (shape == UNSTRUCTURED_HEXAHEDRON) {
            n[k + 4] = b[k] * t;
            dn[k + 4] = vec3(db[k] * t, b[k]);
        }
    }
    if (shape == UNSTRUCTURED_PYRAMID) {
        n[4] = t;
        dn[4] = vec3(0.0, 0.0, 1.0);
    }
}

bool insideReference(uint shape, vec3 q) {
    const float e = UNSTRUCTURED_INSIDE_EPSILON;
    bool box = all(greaterThanEqual(q, vec3(-e))) && all(lessThanEqual(q, vec3(1.0 + e)));
    return shape == UNSTRUCTURED_WEDGE ? box && q.x + q.y <= 1.0 + e : box;
}

// The barycentric coordinates of grid-space point p in the tetrahedron whose corners are indices[first ..]
// (lambda[k]: corner k's), its corners' values and its edges from corner 0; false where they are not finite (a
// cell of no volume was dropped on the host; a nearly flat one gives huge or NaN coordinates).
// p = x0 + edges * lambda.yzw, solved by Cramer's rule.
bool tetrahedronCoordinates(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint first, vec3 p, out vec4 lambda,
                            out vec4 corner, out mat3 edges) {
    vec4 x0 = meshVertex(mesh, h, m.words[first]), x1 = meshVertex(mesh, h, m.words[first + 1u]);
    vec4 x2 = meshVertex(mesh, h, m.words[first + 2u]), x3 = meshVertex(mesh, h, m.words[first + 3u]);
    vec3 e1 = x1.xyz - x0.xyz, e2 = x2.xyz - x0.xyz, e3 = x3.xyz - x0.xyz, r = p - x0.xyz;
    vec3 c23 = cross(e2, e3);
    vec3 b = vec3(dot(r, c23), dot(e1, cross(r, e3)), dot(e1, cross(e2, r))) / dot(e1, c23);
    lambda = vec4(1.0 - b.x - b.y - b.z, b);
    corner = vec4(x0.w, x1.w, x2.w, x3.w);
    edges = mat3(e1, e2, e3);
    return !any(isnan(b)) && !any(isinf(b));
}

// The field of the cell at grid-space point p as its interpolant gives it, also a little outside the cell
// (extrapolated, for the iso-surface's root finding): `inside` whether p is in the cell, and with
// `wantGradient` (a constant at each call) the interpolant's gradient in grid space. False where the
// interpolant cannot be evaluated at p (a singular map, or a point its Newton iteration does not reach).
bool tetrahedronField(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint first, uint cell, vec3 p, bool wantGradient,
                      out float value, out bool inside, out vec3 gradient) {
    value = 0.0;
    inside = false;
    gradient = vec3(0.0);
    vec4 lambda, corner;
    mat3 edges;
    if (!tetrahedronCoordinates(mesh, m, h, first, p, lambda, corner, edges)) return false;
    inside = all(greaterThanEqual(lambda, vec4(-UNSTRUCTURED_INSIDE_EPSILON)));
    if (h.cellCentered != 0u) {
        value = uintBitsToFloat(m.words[h.cellValueOffset + cell]);
    } else {
        value = dot(lambda, corner);
        // f = f0 + (f1 - f0, f2 - f0, f3 - f0) . b with b = E^-1 (p - x0): its gradient is E^-T times that.
        if (wantGradient) gradient = transpose(inverse(edges)) * (corner.yzw - corner.x);
    }
    return true;
}

// The same for a hexahedron, wedge or pyramid with `corners` corners: Newton's method on its map from the
// reference cell's centre, kept near the cell (a point outside may have no preimage); the cell's size
// scales the residual test.
bool isoparametricField(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint shape, uint corners, uint first, uint cell,
                        vec3 p, bool wantGradient, out float value, out bool inside, out vec3 gradient) {
    value = 0.0;
    inside = false;
    gradient = vec3(0.0);
    // Corners and point relative to corner 0: the residual is then rounded at the cell's own scale, not at
    // that of its grid coordinates (up to 2048), which would swamp the tolerance of a cell a unit wide.
    vec3 x[8];
    float corner[8];
    vec4 origin = meshVertex(mesh, h, m.words[first]);
    for (uint k = 0u; k < 8u; ++k) {
        vec4 vertex = k < corners ? meshVertex(mesh, h, m.words[first + k]) : origin;
        x[k] = vertex.xyz - origin.xyz;
        corner[k] = vertex.w;
    }
    p -= origin.xyz;
    vec3 q = shape == UNSTRUCTURED_WEDGE ? vec3(1.0 / 3.0, 1.0 / 3.0, 0.5) : vec3(0.5, 0.5, shape == UNSTRUCTURED_PYRAMID ? 0.25 : 0.5);
    vec3 lo = x[0], hi = x[0];
    for (uint k = 1u; k < corners; ++k) {
        lo = min(lo, x[k]);
        hi = max(hi, x[k]);
    }
    float size = max(hi.x - lo.x, max(hi.y - lo.y, hi.z - lo.z));
    float n[8];
    vec3 dn[8];
    mat3 jacobian;
    for (uint step = 0u; step < UNSTRUCTURED_NEWTON_STEPS; ++step) {
        shapeFunctions(shape, q, n, dn);
        vec3 f = -p;
        jacobian = mat3(0.0);
        for (uint k = 0u; k < corners; ++k) {
            f += n[k] * x[k];
            jacobian += outerProduct(x[k], dn[k]);
        }
        vec3 dq = inverse(jacobian) * f;
        if (any(isnan(dq)) || any(isinf(dq))) return false;
        q = clamp(q - dq, vec3(-0.5), vec3(1.5));
        if (dot(dq, dq) < 1e-12) break;  // converged to 1e-6 of the reference cell
    }
    shapeFunctions(shape, q, n, dn);
    vec3 residual = -p;
    jacobian = mat3(0.0);
    vec3 valueGradient = vec3(0.0);  // of the interpolant in the reference cell
    for (uint k = 0u; k < corners; ++k) {
        residual += n[k] * x[k];
        jacobian += outerProduct(x[k], dn[k]);
        valueGradient += corner[k] * dn[k];
    }
    if (!(length(residual) <= 1e-4 * size)) return false;
    inside = insideReference(shape, q);
    if (h.cellCentered != 0u) {
        value = uintBitsToFloat(m.words[h.cellValueOffset + cell]);
    } else {
        for (uint k = 0u; k < corners; ++k) value += n[k] * corner[k];
        if (wantGradient) gradient = transpose(inverse(jacobian)) * valueGradient;
    }
    return true;
}

bool cellField(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint cell, vec3 p, bool wantGradient, out float value,
               out bool inside, out vec3 gradient) {
    uint word = m.words[h.cellOffset + cell];
    uint shape = word & 3u, first = h.indexOffset + (word >> 2u);
    if (shape == UNSTRUCTURED_TETRAHEDRON) return tetrahedronField(mesh, m, h, first, cell, p, wantGradient, value, inside, gradient);
    uint corners = shape == UNSTRUCTURED_HEXAHEDRON ? 8u : shape == UNSTRUCTURED_WEDGE ? 6u : 5u;
    return isoparametricField(mesh, m, h, shape, corners, first, cell, p, wantGradient, value, inside, gradient);
}

// Whether grid-space point p lies in leaf-order cell `cell`, and the field's value there.
bool cellValue(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint cell, vec3 p, out float value) {
    bool inside;
    vec3 gradient;
    return cellField(mesh, m, h, cell, p, false, value, inside, gradient) && inside;
}

bool boxHolds(vec4 lo, vec4 hi, vec3 p) {
    return all(greaterThanEqual(p, lo.xyz)) && all(lessThanEqual(p, hi.xyz));
}

UnstructuredHeader unstructuredHeader(uint64_t mesh) {
    MeshWordsRef m = MeshWordsRef(mesh);
    return UnstructuredHeader(m.words[0], m.words[1], m.words[2], m.words[3], m.words[4], m.words[5], m.words[6],
                              m.words[7], m.words[8], m.words[9], m.words[10], m.words[11], m.words[12],
                              m.words[13], m.words[14]);
}

// The walk to grid-space point p from its start cell's tetrahedron (UnstructuredHeader.startCellOffset),
// across the face opposite the corner of most negative barycentric coordinate at each step, through at most
// UNSTRUCTURED_WALK_STEPS cells: true with `value` the field in the tetrahedron holding p; false where the
// mesh has no tetrahedra or the start cell none, or the walk leaves the tetrahedra (the mesh's boundary, a
// cell of another shape, a flat cell) or runs out of steps. Start cells are about half the median cell wide,
// so a walk mostly takes a few cell tests, where the BVH's descent tests every cell whose box holds p.
bool unstructuredWalk(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, vec3 p, uint startIndex, out float value) {
    value = 0.0;
    if (h.neighbours == UNSTRUCTURED_NEIGHBOURS_NONE) return false;
    uint cell = m.words[h.startCellOffset + startIndex];
    for (uint step = 0u; step < UNSTRUCTURED_WALK_STEPS && cell != UNSTRUCTURED_NO_CELL; ++step) {
        // Every cell a tetrahedron: cell c's 8 words are at 8c.
        uint first = h.indexOffset + 8u * cell;
        if (h.neighbours != UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA) {
            uint word = m.words[h.cellOffset + cell];
            if ((word & 3u) != UNSTRUCTURED_TETRAHEDRON) return false;
            first = h.indexOffset + (word >> 2u);
        }
        vec4 lambda, corner;
        mat3 edges;
        if (!tetrahedronCoordinates(mesh, m, h, first, p, lambda, corner, edges)) return false;
        float lowest = min(min(lambda.x, lambda.y), min(lambda.z, lambda.w));
        if (lowest >= -UNSTRUCTURED_INSIDE_EPSILON) {
            value = h.cellCentered != 0u ? uintBitsToFloat(m.words[h.cellValueOffset + cell]) : dot(lambda, corner);
            return true;
        }
        uint across = lambda.x == lowest ? 0u : lambda.y == lowest ? 1u : lambda.z == lowest ? 2u : 3u;
        cell = m.words[first + 4u + across];
    }
    return false;
}

// The start cell holding grid-space point p, clamped to the grid of them (x fastest). A start cell spans
// startPerMacrocell / 8 grid units: the scale is exact, so the host's float product gives the same cell.
uint unstructuredStartIndex(UnstructuredHeader h, vec3 p) {
    uvec3 at = uvec3(clamp(ivec3(floor(p * (float(h.startPerMacrocell) * 0.125))), ivec3(0), ivec3(h.startX, h.startY, h.startZ) - 1));
    return (at.z * h.startY + at.y) * h.startX + at.x;
}

// The field of the mesh at `mesh` (a device address; `h` its header) at grid-space point p: false where no
// cell holds p. The query walks from the start cell's tetrahedron; where that walk does not end in a cell (and
// in meshes without tetrahedra) it descends the BVH from the start cell's node. A start cell that no cell
// overlaps has neither, and returns at once.
bool unstructuredValue(uint64_t mesh, UnstructuredHeader h, vec3 p, out float value) {
    value = 0.0;
    MeshWordsRef m = MeshWordsRef(mesh);
    if (h.nodeCount == 0u) return false;
    uint startIndex = unstructuredStartIndex(h, p);
    if (unstructuredWalk(mesh, m, h, p, startIndex, value)) return true;
    uint node = m.words[h.startOffset + startIndex];
    if (node == UNSTRUCTURED_NO_NODE) return false;
    MeshNodesRef nodes = MeshNodesRef(mesh + 4ul * uint64_t(h.nodeOffset));
    uint stack[BVH_MAX_DEPTH];
    uint top = 0u;
    // Nodes visited, bounded (the tree has nodeCount of them); lavapipe ends any one loop after 65,535
    // iterations, so the descent is two nested loops.
    for (uint chunk = 0u; chunk < 64u; ++chunk) {
        for (uint visit = 0u; visit < 32768u; ++visit) {
            BvhNode n = nodes.nodes[node];
            bool descended = false;
            for (int side = 0; side < 2; ++side) {
                vec4 lo = side == 0 ? n.leftMin : n.rightMin, hi = side == 0 ? n.leftMax : n.rightMax;
                uint ref = floatBitsToUint(lo.w), count = floatBitsToUint(hi.w);
                if (count == 0u && ref == 0u) continue;  // empty child (a tree of one leaf)
                if (!boxHolds(lo, hi, p)) continue;
                if (count > 0u) {
                    for (uint c = ref; c < ref + count; ++c)
                        if (cellValue(mesh, m, h, c, p, value)) return true;
                } else if (!descended) {
                    node = ref;
                    descended = true;
                } else if (top < BVH_MAX_DEPTH) {
                    stack[top++] = ref;
                }
            }
            if (!descended) {
                if (top == 0u) return false;
                node = stack[--top];
            }
        }
    }
    return false;
}

// Iso-surfaces in mesh cells (shared/scene.h IsoCellPrim with a mesh address): where the cell's own
// interpolant equals the isovalue along the ray. The ray's segment in the cell's box (grown by 1e-4 of it)
// is cut into 16 even steps; at each step's ends the interpolant and its derivative along the ray are
// evaluated (extrapolated past the cell where its map reaches). The nearest step whose ends straddle the
// isovalue is bisected to float precision, and the root counts where it lies inside the cell. A step whose
// ends do not straddle it is split, as structured cells split theirs (intersect.glsl), at a turning point of
// the cubic the ends' values and derivatives define (Hermite) where that cubic turns back across the
// isovalue. In a tetrahedron the field is linear along the ray and in a hexahedron of parallel faces a cubic,
// so there the cubic is exact and a double crossing within a step is found; in a curved cell one the cubic
// does not show is missed, and of three crossings within one step the one bisection finds is taken.
vec3 isoMeshPoint(IsoCellPrim prim, vec3 objectPoint) {
    return (objectPoint - prim.values1.xyz) * prim.values0.xyz;
}

// The cell's interpolant at go + t gd and, with `derivative` (a constant at each call), its derivative in t
// (else 0); false where it cannot be evaluated.
bool meshIsoSample(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint cell, vec3 go, vec3 gd, float t, bool derivative,
                   out float f, out float df) {
    bool inside;
    vec3 gradient;
    bool ok = cellField(mesh, m, h, cell, go + t * gd, derivative, f, inside, gradient);
    df = dot(gradient, gd);
    return ok && !isnan(df) && !isinf(df);
}

// The crossing in [a, b], whose values fa, fb straddle the isovalue, bisected to float precision: true and
// tBest set where it lies inside the cell and in (tmin, tBest).
bool meshIsoBisect(uint64_t mesh, MeshWordsRef m, UnstructuredHeader h, uint cell, vec3 go, vec3 gd, float iso, float a, float b,
                   bool below, float tmin, inout float tBest) {
    vec3 unused;
    bool inside;
    for (int it = 0; it < 40; ++it) {
        float mid = 0.5 * (a + b);
        if (mid <= a || mid >= b) break;  // no float between the ends: converged
        float fm;
        if (!cellField(mesh, m, h, cell, go + mid * gd, false, fm, inside, unused)) break;
        if ((fm < iso) == below) a = mid;
        else b = mid;
    }
    float fr;
    bool found = cellField(mesh, m, h, cell, go + b * gd, false, fr, inside, unused) && inside;
    if (!found || !(b > tmin && b < tBest)) return false;
    tBest = b;
    return true;
}

bool intersectMeshIsoCell(vec3 origin, vec3 direction, IsoCellPrim prim, float tmin, inout float tBest) {
    vec3 lo = prim.lowCorner.xyz, size = prim.size.xyz;
    vec3 grow = 1e-4 * size + 4e-7 * abs(lo);
    vec3 inv = vec3(1.0) / mix(direction, vec3(1e-30), equal(direction, vec3(0.0)));
    vec3 t0 = (lo - grow - origin) * inv, t1 = (lo + size + grow - origin) * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, tmin));
    float leave = min(min(tf.x, tf.y), min(tf.z, tBest));
    if (!(enter < leave)) return false;
    uint64_t mesh = packUint2x32(uvec2(prim.meshLow, prim.meshHigh));
    MeshWordsRef m = MeshWordsRef(mesh);
    UnstructuredHeader h = unstructuredHeader(mesh);
    uint cell = floatBitsToUint(prim.values0.w);
    float iso = prim.lowCorner.w;
    vec3 go = isoMeshPoint(prim, origin), gd = direction * prim.values0.xyz;
    vec3 unused;
    bool inside;
    // Along the ray the field is linear in a tetrahedron: no derivatives, and no turning point to split at.
    bool tetrahedron = (m.words[h.cellOffset + cell] & 3u) == UNSTRUCTURED_TETRAHEDRON;
    float fa, da;
    bool okA = tetrahedron ? meshIsoSample(mesh, m, h, cell, go, gd, enter, false, fa, da)
                           : meshIsoSample(mesh, m, h, cell, go, gd, enter, true, fa, da);
    float ta = enter;
    const uint STEPS = 16u;
    for (uint k = 1u; k <= STEPS; ++k) {
        float tb = mix(enter, leave, float(k) / float(STEPS));
        float fb, db;
        bool okB = tetrahedron ? meshIsoSample(mesh, m, h, cell, go, gd, tb, false, fb, db)
                               : meshIsoSample(mesh, m, h, cell, go, gd, tb, true, fb, db);
        if (okA && okB && (fa < iso) != (fb < iso)) {
            if (meshIsoBisect(mesh, m, h, cell, go, gd, iso, ta, tb, fa < iso, tmin, tBest)) return true;
        } else if (okA && okB && !tetrahedron) {
            // Both ends on one side: the surface may still cross twice within the step. Where the Hermite cubic
            // over the step (fa + c1 s + c2 s^2 + c3 s^3, s = 0..1) turns back across the isovalue, the
            // interpolant at that turning point splits the step into two pieces that straddle it.
            float len = tb - ta;
            float c1 = len * da, c2 = 3.0 * (fb - fa) - len * (2.0 * da + db), c3 = 2.0 * (fa - fb) + len * (da + db);
            float split[2];
            uint splits = cubicExtrema(3.0 * c3, 2.0 * c2, c1, 1.0, split[0], split[1]);
            for (uint e = 0u; e < splits; ++e) {
                float se = split[e], te = mix(ta, tb, se), ve;
                if ((fa + se * (c1 + se * (c2 + se * c3)) < iso) == (fa < iso)) continue;
                if (!cellField(mesh, m, h, cell, go + te * gd, false, ve, inside, unused) || (ve < iso) == (fa < iso)) continue;
                if (meshIsoBisect(mesh, m, h, cell, go, gd, iso, ta, te, fa < iso, tmin, tBest)) return true;
                if (meshIsoBisect(mesh, m, h, cell, go, gd, iso, te, tb, ve < iso, tmin, tBest)) return true;
            }
        }
        ta = tb;
        fa = fb;
        da = db;
        okA = okB;
    }
    return false;
}

// The gradient of the cell's interpolant at an object-space point on its iso-surface (object space): the
// surface's normal direction, pointing to higher values.
vec3 meshIsoGradient(IsoCellPrim prim, vec3 objectPoint) {
    uint64_t mesh = packUint2x32(uvec2(prim.meshLow, prim.meshHigh));
    float value;
    bool inside;
    vec3 gradient;
    cellField(mesh, MeshWordsRef(mesh), unstructuredHeader(mesh), floatBitsToUint(prim.values0.w), isoMeshPoint(prim, objectPoint),
              true, value, inside, gradient);
    return gradient * prim.values0.xyz;  // d/dx = d/dg * scale
}

#endif
