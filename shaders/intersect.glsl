// Ray/box, ray/triangle, ray/sphere and ray/cylinder tests used by the traversal kernels. The triangle
// test is watertight (Woop, Benthin & Wald 2013): rays through shared edges and vertices never slip
// between triangles. The box test is conservative (Ize 2013): tmax is widened by 2*gamma(3) so rounding
// never culls a box the ray really enters. Sphere and cylinder roots use the stable form of Haines et al.
// (Ray Tracing Gems, ch. 7).
#ifndef RIPPLE_INTERSECT_GLSL
#define RIPPLE_INTERSECT_GLSL
#include "cubic.glsl"
#include "features.glsl"
#include "unstructured.glsl"

// Per-ray constants of the watertight test: the axis permutation and shear.
struct TriangleRay {
    vec3 origin;
    ivec3 k;       // kx, ky, kz: kz is the dominant axis of the direction
    vec3 shear;    // Sx, Sy, Sz
};

TriangleRay makeTriangleRay(vec3 origin, vec3 direction) {
    TriangleRay r;
    r.origin = origin;
    vec3 a = abs(direction);
    int kz = (a.x > a.y) ? ((a.x > a.z) ? 0 : 2) : ((a.y > a.z) ? 1 : 2);
    int kx = (kz + 1) % 3;
    int ky = (kx + 1) % 3;
    if (direction[kz] < 0.0) { int t = kx; kx = ky; ky = t; }  // keep the winding
    r.k = ivec3(kx, ky, kz);
    r.shear = vec3(direction[kx] / direction[kz], direction[ky] / direction[kz], 1.0 / direction[kz]);
    return r;
}

// Returns true and updates (t, u, v) when the triangle is hit with tmin < t < tBest.
bool intersectTriangle(TriangleRay r, vec3 v0, vec3 v1, vec3 v2, float tmin, inout float tBest, out float u,
                       out float v) {
    u = 0.0;
    v = 0.0;
    vec3 A = v0 - r.origin;
    vec3 B = v1 - r.origin;
    vec3 C = v2 - r.origin;
    float Ax = A[r.k.x] - r.shear.x * A[r.k.z];
    float Ay = A[r.k.y] - r.shear.y * A[r.k.z];
    float Bx = B[r.k.x] - r.shear.x * B[r.k.z];
    float By = B[r.k.y] - r.shear.y * B[r.k.z];
    float Cx = C[r.k.x] - r.shear.x * C[r.k.z];
    float Cy = C[r.k.y] - r.shear.y * C[r.k.z];
    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = U + V + W;
    if (det == 0.0) return false;
    float Az = r.shear.z * A[r.k.z];
    float Bz = r.shear.z * B[r.k.z];
    float Cz = r.shear.z * C[r.k.z];
    float T = U * Az + V * Bz + W * Cz;
    // Compare T against the interval scaled by det, so no division happens for misses.
    float sgn = det < 0.0 ? -1.0 : 1.0;
    float absDet = abs(det);
    float sT = T * sgn;
    if (sT <= tmin * absDet || sT >= tBest * absDet) return false;
    float inv = 1.0 / det;
    float t = T * inv;
    if (!(t > tmin && t < tBest)) return false;  // the division may round across the bounds
    tBest = t;
    u = V * inv;
    v = W * inv;
    return true;
}

// Nearest root of a quadratic in the form the sphere and cylinder tests share: |f + t d|^2 = r^2 with f and
// d already reduced to the components that matter. The discriminant b^2 - a*c is formed as
// a * (r^2 - |f - (b/a) d|^2), which does not cancel for small shapes far away, and the roots come from
// the cancellation-free pair c/q and q/a. Returns the roots in order; false when there are none.
bool stableQuadraticRoots(vec3 f, vec3 d, float r, out float t0, out float t1) {
    t0 = 0.0;
    t1 = 0.0;
    float a = dot(d, d);
    if (!(a > 0.0)) return false;
    float b = dot(f, d);  // half the linear coefficient
    vec3 l = f - (b / a) * d;
    float disc = a * (r * r - dot(l, l));
    if (disc < 0.0) return false;
    float c = dot(f, f) - r * r;
    float q = -b - (b < 0.0 ? -1.0 : 1.0) * sqrt(disc);
    t0 = c / q;
    t1 = q / a;
    if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
    return true;
}

// Round cylinder from p0 to p1 (radius in p0Radius.w), with flat caps at the ends named by `caps`
// (CAP_FIRST, CAP_SECOND). The ray is
// split into components along and across the unit axis, so the side is the 2D circle problem of the
// sphere test. Returns true and updates tBest, `axial` (0 at p0, 1 at p1) and `onCap` (0 side, 1 cap)
// for the nearest hit in (tmin, tBest).
bool intersectCylinder(vec3 origin, vec3 direction, vec4 p0Radius, vec3 p1, uint caps, float tmin,
                       inout float tBest, out float axial, out float onCap) {
    axial = 0.0;
    onCap = 0.0;
    vec3 p0 = p0Radius.xyz;
    float r = p0Radius.w;
    vec3 axis = p1 - p0;
    float len = length(axis);
    vec3 w = axis / len;
    vec3 f = origin - p0;
    float fa = dot(f, w);
    float da = dot(direction, w);
    vec3 fp = f - fa * w;          // across the axis
    vec3 dp = direction - da * w;
    bool found = false;
    float t0, t1;
    if (stableQuadraticRoots(fp, dp, r, t0, t1)) {
        for (int i = 0; i < 2; ++i) {
            float t = i == 0 ? t0 : t1;
            float s = fa + t * da;
            if (t > tmin && t < tBest && s >= 0.0 && s <= len) {
                tBest = t;
                axial = s / len;
                found = true;
                break;
            }
        }
    }
    if (caps != 0u && da != 0.0) {
        for (int i = 0; i < 2; ++i) {
            if ((caps & (i == 0 ? CAP_FIRST : CAP_SECOND)) == 0u) continue;
            float end = i == 0 ? 0.0 : len;
            float t = (end - fa) / da;
            vec3 across = fp + t * dp;
            if (t > tmin && t < tBest && dot(across, across) <= r * r) {
                tBest = t;
                axial = float(i);
                onCap = 1.0;
                found = true;
            }
        }
    }
    return found;
}

// Returns true and updates tBest with the nearest root in (tmin, tBest).
bool intersectSphere(vec3 origin, vec3 direction, vec4 centerRadius, float tmin, inout float tBest) {
    float t0, t1;
    if (!stableQuadraticRoots(origin - centerRadius.xyz, direction, centerRadius.w, t0, t1)) return false;
    float t = t0 > tmin ? t0 : t1;
    if (!(t > tmin && t < tBest)) return false;
    tBest = t;
    return true;
}

// Cone frustum from p0 (radius r0) to p1 (radius r1) with the caps named in `flags`; with CONE_ROUND, a
// curve segment: spheres at both ends joined by the cone tangent to both. The ray is first moved to its
// point nearest the segment's middle, so the quadratic's coefficients stay small for a thin cone seen
// from far away (the cancellation that ruins the textbook form), and the roots come from the
// cancellation-free pair q/a, c/q. Returns true and updates tBest, `axial` (0 at p0, 1 at p1) and `part`
// (0 side, 1 flat cap, 2 end sphere) for the nearest hit in (tmin, tBest).
bool intersectCone(vec3 origin, vec3 direction, vec4 p0Radius, vec4 p1Radius, uint flags, float tmin,
                   inout float tBest, out float axial, out float part) {
    axial = 0.0;
    part = 0.0;
    bool found = false;
    vec3 axis = p1Radius.xyz - p0Radius.xyz;
    float len = length(axis);
    vec3 w = axis / len;
    bool round = (flags & CONE_ROUND) != 0u;
    if (round) {
        for (int i = 0; i < 2; ++i) {
            vec4 sphere = i == 0 ? p0Radius : p1Radius;
            float t0, t1;
            if (!stableQuadraticRoots(origin - sphere.xyz, direction, sphere.w, t0, t1)) continue;
            float t = t0 > tmin ? t0 : t1;
            if (t > tmin && t < tBest) {
                tBest = t;
                axial = float(i);
                part = 2.0;
                found = true;
            }
        }
    }
    // The side: for a round segment, the cone tangent to both spheres, which touches them a little
    // behind their centres (by r sin(alpha), with sin(alpha) the radius change per unit length).
    vec3 p0 = p0Radius.xyz;
    float r0 = p0Radius.w;
    float r1 = p1Radius.w;
    float sideStart = 0.0;
    float sideEnd = len;
    if (round) {
        float sinAlpha = (r1 - r0) / len;
        if (abs(sinAlpha) >= 1.0) return found;  // one sphere holds the other: no side
        float cosAlpha = sqrt(1.0 - sinAlpha * sinAlpha);
        sideStart = -r0 * sinAlpha;
        sideEnd = len - r1 * sinAlpha;
        r0 *= cosAlpha;
        r1 *= cosAlpha;
    }
    float slope = (r1 - r0) / (sideEnd - sideStart);
    float dd = dot(direction, direction);
    float shift = dot(0.5 * (p0Radius.xyz + p1Radius.xyz) - origin, direction) / dd;
    vec3 f = origin + shift * direction - p0;
    float fa = dot(f, w);
    float da = dot(direction, w);
    vec3 fp = f - fa * w;
    vec3 dp = direction - da * w;
    float rf = r0 + slope * (fa - sideStart);  // radius of the cone at the shifted origin's axial position
    // |fp + t dp|^2 = (rf + slope da t)^2, as a t^2 + 2 b t + c = 0
    float a = dot(dp, dp) - slope * slope * da * da;
    float b = dot(fp, dp) - rf * slope * da;
    float c = dot(fp, fp) - rf * rf;
    float disc = b * b - a * c;
    if (disc >= 0.0) {
        float q = -b - (b < 0.0 ? -1.0 : 1.0) * sqrt(disc);
        float roots[2];
        roots[0] = q != 0.0 ? c / q : uintBitsToFloat(0xff800000u);  // -inf: no root
        roots[1] = abs(a) > 0.0 ? q / a : uintBitsToFloat(0xff800000u);
        for (int i = 0; i < 2; ++i) {
            float s = fa + roots[i] * da;
            float t = roots[i] + shift;
            float radiusThere = rf + slope * roots[i] * da;
            if (t > tmin && t < tBest && s >= sideStart && s <= sideEnd && radiusThere >= 0.0) {
                tBest = t;
                axial = s / len;
                part = 0.0;
                found = true;
            }
        }
    }
    uint caps = round ? 0u : flags;
    if (caps != 0u && da != 0.0) {
        for (int i = 0; i < 2; ++i) {
            if ((caps & (i == 0 ? CAP_FIRST : CAP_SECOND)) == 0u) continue;
            float t = ((i == 0 ? 0.0 : len) - fa) / da;
            vec3 across = fp + t * dp;
            float r = i == 0 ? r0 : r1;
            if (t + shift > tmin && t + shift < tBest && dot(across, across) <= r * r) {
                tBest = t + shift;
                axial = float(i);
                part = 1.0;
                found = true;
            }
        }
    }
    return found;
}

// 1 + 2*gamma(3) with gamma(n) = n*u/(1-n*u), u = 2^-24: the widening that makes the slab test conservative.
const float BOX_TMAX_SCALE = 1.0000003576;

// Entry distance of the ray into the box, or +inf when it misses or lies beyond tFar.
float intersectBox(vec3 lo, vec3 hi, vec3 origin, vec3 invDirection, float tmin, float tFar) {
    vec3 t0 = (lo - origin) * invDirection;
    vec3 t1 = (hi - origin) * invDirection;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, tmin));
    float leave = min(min(tf.x, tf.y), min(tf.z, tFar)) * BOX_TMAX_SCALE;
    return enter <= leave ? enter : uintBitsToFloat(0x7f800000u);
}

// Reciprocal direction with zero components replaced by a huge finite value of the right sign, so
// 0 * inf never produces NaN in the slab test.
vec3 safeReciprocal(vec3 d) {
    const float tiny = 1e-30;
    vec3 s = vec3(d.x < 0.0 ? -tiny : tiny, d.y < 0.0 ? -tiny : tiny, d.z < 0.0 ? -tiny : tiny);
    return 1.0 / mix(d, s, lessThan(abs(d), vec3(tiny)));
}

// Iso-surface inside one cell of a structured-regular field (Marmitt et al. 2004, "Fast and accurate
// ray-voxel intersection techniques for iso-surface ray tracing"). Along the ray the trilinear interpolant
// of the cell's corner values is a cubic in the distance s travelled inside the cell; the roots of its
// derivative split the segment into pieces where it is monotone, and the nearest piece whose ends differ in
// sign holds the nearest crossing, found by bisection to float precision. No fixed-step marching: a
// crossing is missed only where the surface only touches the ray (a double root), which has measure zero.
// The cubic is formed relative to the cell's corner and the ray's entry point, so it stays well
// conditioned for cells far from the origin.
float isoCubic(vec4 k, float s) {
    return ((k.x * s + k.y) * s + k.z) * s + k.w;
}

// Returns true and updates tBest when the iso-surface in `cell` is crossed with tmin < t < tBest.
bool intersectIsoCell(vec3 origin, vec3 direction, IsoCellPrim cell, float tmin, inout float tBest) {
    if (hasFeature(FEATURE_MESH_ISOSURFACES) && (cell.meshLow | cell.meshHigh) != 0u)
        return intersectMeshIsoCell(origin, direction, cell, tmin, tBest);
    vec3 lo = cell.lowCorner.xyz;
    vec3 inv = safeReciprocal(direction);
    // The cell's box grown by a few ulps of its coordinates: neighbouring cells compute their shared face
    // from different corners, which round differently, and a crossing in the sliver between would be lost.
    // The cubic holds just outside the cell as well.
    vec3 grow = 4e-7 * (abs(lo) + cell.size.xyz);
    vec3 t0 = (lo - grow - origin) * inv;
    vec3 t1 = (lo + cell.size.xyz + grow - origin) * inv;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, tmin));
    float leave = min(min(tf.x, tf.y), min(tf.z, tBest));
    if (!(enter < leave)) return false;

    // Cell-local coordinates (0..1 across the cell) along the ray: a + s * b for s in [0, length].
    vec3 a = (origin + enter * direction - lo) / cell.size.xyz;
    vec3 b = direction / cell.size.xyz;
    float len = leave - enter;
    // The corner factors (1 - x) and x of the trilinear weights, each linear in s: p + s * q.
    vec3 p[2] = vec3[2](vec3(1.0) - a, a);
    vec3 q[2] = vec3[2](-b, b);
    vec4 k = vec4(0.0, 0.0, 0.0, -cell.lowCorner.w);  // s^3, s^2, s, 1 coefficients, minus the isovalue
    for (int n = 0; n < 8; ++n) {
        int i = n & 1, j = (n >> 1) & 1, l = n >> 2;
        float c = n < 4 ? cell.values0[n] : cell.values1[n - 4];
        float px = p[i].x, qx = q[i].x, py = p[j].y, qy = q[j].y, pz = p[l].z, qz = q[l].z;
        k += c * vec4(qx * qy * qz, qx * qy * pz + qx * py * qz + px * qy * qz,
                      qx * py * pz + px * qy * pz + px * py * qz, px * py * pz);
    }

    // Extrema of the cubic inside (0, len): roots of 3 k.x s^2 + 2 k.y s + k.z, in order.
    float pieces[4] = float[4](0.0, len, len, len);
    uint count = 1u + cubicExtrema(3.0 * k.x, 2.0 * k.y, k.z, len, pieces[1], pieces[2]);
    pieces[count] = len;

    float ga = isoCubic(k, 0.0);
    for (uint piece = 0u; piece < count; ++piece) {
        float sa = pieces[piece], sb = pieces[piece + 1u];
        float gb = isoCubic(k, sb);
        if (ga == 0.0 && (piece > 0u || enter > tmin)) {  // on the surface where the piece starts
            sb = sa;
        } else if ((ga < 0.0) != (gb < 0.0) || gb == 0.0) {
            float g0 = ga;
            for (int it = 0; it < 40 && sb - sa > 0.0; ++it) {
                float mid = 0.5 * (sa + sb);
                if (mid <= sa || mid >= sb) break;  // no float between the ends: converged
                float gm = isoCubic(k, mid);
                if ((gm < 0.0) == (g0 < 0.0) && gm != 0.0) sa = mid;
                else sb = mid;
            }
        } else {
            ga = gb;
            continue;
        }
        float t = enter + sb;
        if (t > tmin && t < tBest) {
            tBest = t;
            return true;
        }
        if (t >= tBest) return false;  // later pieces lie farther still
        ga = gb;                        // a crossing at the ray's start (its own surface): look on
    }
    return false;
}

#endif
