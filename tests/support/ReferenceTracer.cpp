// Brute-force double-precision reference tracer: validity rules shared with core::Scene, a watertight
// triangle test with exact edge signs, stable sphere and cylinder tests, and oneTBB loops over rays.
#include "tests/support/ReferenceTracer.h"

#include "core/scene/PreparedGeometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ripple::test {

using glm::dvec3;

// ---------------------------------------------------------------------------------------------------
// Validity

uint32_t triangleCount(const core::TriangleMesh& mesh) {
    if (!mesh.indices.empty()) return static_cast<uint32_t>(mesh.indices.size());
    return static_cast<uint32_t>(mesh.positions.size() / 3);
}

glm::uvec3 triangleIndices(const core::TriangleMesh& mesh, uint32_t tri) {
    if (!mesh.indices.empty()) return mesh.indices[tri];
    return glm::uvec3(3u * tri, 3u * tri + 1u, 3u * tri + 2u);
}

bool isFinite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool isTriangleValid(const core::TriangleMesh& mesh, uint32_t tri) {
    if (tri >= triangleCount(mesh)) return false;
    const glm::uvec3 idx = triangleIndices(mesh, tri);
    const size_t n = mesh.positions.size();
    if (idx.x >= n || idx.y >= n || idx.z >= n) return false;
    const glm::vec3& a = mesh.positions[idx.x];
    const glm::vec3& b = mesh.positions[idx.y];
    const glm::vec3& c = mesh.positions[idx.z];
    if (!isFinite(a) || !isFinite(b) || !isFinite(c)) return false;
    // Differences of floats and their products are far inside double's range, so a zero here means the
    // vertices really are collinear (or coincident), not that something underflowed.
    const dvec3 n3 = glm::cross(dvec3(b) - dvec3(a), dvec3(c) - dvec3(a));
    return glm::dot(n3, n3) != 0.0;
}

uint32_t sphereCount(const core::SphereSet& set) { return static_cast<uint32_t>(set.centers.size()); }

float sphereRadius(const core::SphereSet& set, uint32_t i) {
    if (set.radii.size() == set.centers.size()) return set.radii[i];
    if (set.radii.size() == 1) return set.radii[0];
    return 0.0f;  // core::Scene skips a set whose radius count is neither 1 nor one per center
}

bool isSphereValid(const core::SphereSet& set, uint32_t i) {
    if (i >= sphereCount(set)) return false;
    const float r = sphereRadius(set, i);
    return isFinite(set.centers[i]) && std::isfinite(r) && r > 0.0f;
}

uint32_t cylinderCount(const core::CylinderSet& set) {
    return static_cast<uint32_t>(set.indices.empty() ? set.positions.size() / 2 : set.indices.size());
}

glm::uvec2 cylinderIndices(const core::CylinderSet& set, uint32_t i) {
    if (!set.indices.empty()) return set.indices[i];
    return glm::uvec2(2u * i, 2u * i + 1u);
}

float cylinderRadius(const core::CylinderSet& set, uint32_t i) {
    if (set.radii.size() == cylinderCount(set)) return set.radii[i];
    if (set.radii.size() == 1) return set.radii[0];
    return 0.0f;
}

bool isCylinderValid(const core::CylinderSet& set, uint32_t i) {
    if (i >= cylinderCount(set)) return false;
    const glm::uvec2 idx = cylinderIndices(set, i);
    if (idx.x >= set.positions.size() || idx.y >= set.positions.size()) return false;
    const glm::vec3 &a = set.positions[idx.x], &b = set.positions[idx.y];
    const float r = cylinderRadius(set, i);
    if (!isFinite(a) || !isFinite(b) || !(std::isfinite(r) && r > 0.0f)) return false;
    const glm::vec3 axis = b - a;  // in float, as core::Scene decides
    return glm::dot(axis, axis) >= std::numeric_limits<float>::min();
}

bool isTransformValid(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;  // not affine
    return std::abs(glm::determinant(glm::dmat3(m))) > kSingularDeterminant;
}

bool hasValidPrimitive(const core::SceneDescription& scene, const core::GeometryRef& geometry) {
    switch (geometry.kind) {
    case core::GeometryKind::Triangles: {
        if (geometry.index >= scene.meshes.size()) return false;
        const core::TriangleMesh& mesh = scene.meshes[geometry.index];
        for (uint32_t t = 0; t < triangleCount(mesh); ++t)
            if (isTriangleValid(mesh, t)) return true;
        return false;
    }
    case core::GeometryKind::Spheres: {
        if (geometry.index >= scene.sphereSets.size()) return false;
        const core::SphereSet& set = scene.sphereSets[geometry.index];
        for (uint32_t s = 0; s < sphereCount(set); ++s)
            if (isSphereValid(set, s)) return true;
        return false;
    }
    case core::GeometryKind::Cones:
        return geometry.index < scene.coneSets.size() &&
               !core::prepareGeometry(scene.coneSets[geometry.index], bvh::BuildOptions{})->validPrims.empty();
    case core::GeometryKind::Cylinders: {
        if (geometry.index >= scene.cylinderSets.size()) return false;
        const core::CylinderSet& set = scene.cylinderSets[geometry.index];
        for (uint32_t c = 0; c < cylinderCount(set); ++c)
            if (isCylinderValid(set, c)) return true;
        return false;
    }
    case core::GeometryKind::Isosurfaces: return false;  // not traced here: tests check them analytically
    }
    return false;  // a kind value outside the enum
}

bool isInstanceValid(const core::SceneDescription& scene, const core::InstanceDescription& instance) {
    return isTransformValid(instance.transform) && hasValidPrimitive(scene, instance.geometry);
}

// ---------------------------------------------------------------------------------------------------
// Intersection

namespace {

struct ObjectRay {
    dvec3 origin;
    dvec3 direction;
    double tmin;
    double tmax;
};

// Error-free transformations (Knuth's TwoSum, FMA TwoProduct): a + b = s + e and a * b = p + e exactly.
void twoSum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bVirtual = s - a, aVirtual = s - bVirtual;
    e = (a - aVirtual) + (b - bVirtual);
}

// Exact sign of x0 + x1 + x2 + x3: Shewchuk's grow-expansion turns the terms into a nonoverlapping
// expansion, whose sign is that of its largest nonzero component.
double exactSignOfSum(const double (&x)[4]) {
    double h[4];
    int n = 0;
    for (double q : x) {
        for (int i = 0; i < n; ++i) {
            double s, e;
            twoSum(q, h[i], s, e);
            h[i] = e;
            q = s;
        }
        h[n++] = q;
    }
    for (int i = n - 1; i >= 0; --i)
        if (h[i] != 0.0) return h[i] > 0.0 ? 1.0 : -1.0;
    return 0.0;
}

// a * b - c * d with a sign that is exact. The double result is right whenever it is larger than its
// rounding error bound (Shewchuk's orient2d filter); below that the sign comes from an exact expansion.
// An exact sign makes the edge test a consistent predicate on the projected vertices: across a shared
// edge the two triangles get opposite signs, and around a shared vertex the fan is never left with a gap
// (a merely antisymmetric evaluation can still have every spoke of a fan round the same way).
double exactSignDifferenceOfProducts(double a, double b, double c, double d) {
    const double ab = a * b, cd = c * d;
    const double r = ab - cd;
    if (std::abs(r) > 0x1p-50 * (std::abs(ab) + std::abs(cd))) return r;
    const double sign = exactSignOfSum({ab, std::fma(a, b, -ab), -cd, -std::fma(c, d, -cd)});
    if (sign == 0.0) return 0.0;
    return std::copysign(std::max(std::abs(r), std::numeric_limits<double>::denorm_min()), sign);
}

struct TriangleHit {
    double t, u, v;
};

// The ray in the frame of Woop, Benthin and Wald (2013): vertices relative to the origin are sheared so
// the ray runs along +z through (0, 0); each vertex is projected by the same arithmetic in every triangle
// that shares it, so neighbours see bit-identical 2D points. The shear is kept as three rows with exact
// 0 and 1 entries, which gives the same values as indexing by axis without a branch per component.
struct RayFrame {
    dvec3 rowX, rowY, rowZ;

    explicit RayFrame(const dvec3& d) {
        const dvec3 a = glm::abs(d);
        const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
        const int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
        rowX = rowY = rowZ = dvec3(0.0);
        rowX[kx] = 1.0;
        rowX[kz] = -d[kx] / d[kz];
        rowY[ky] = 1.0;
        rowY[kz] = -d[ky] / d[kz];
        rowZ[kz] = 1.0 / d[kz];
    }
    dvec3 project(const dvec3& p) const { return dvec3(glm::dot(p, rowX), glm::dot(p, rowY), glm::dot(p, rowZ)); }
};

// Watertight test in double on the sheared frame; edges and vertices count as inside, for either winding.
// Returns false on a miss or when the ray lies in the triangle's plane.
bool intersectTriangle(const ObjectRay& ray, const RayFrame& frame, const dvec3& a, const dvec3& b, const dvec3& c,
                       TriangleHit& hit) {
    const dvec3 A = frame.project(a - ray.origin), B = frame.project(b - ray.origin), C = frame.project(c - ray.origin);
    const double U = exactSignDifferenceOfProducts(C.x, B.y, C.y, B.x);  // weight of a: the edge opposite it
    const double V = exactSignDifferenceOfProducts(A.x, C.y, A.y, C.x);
    if ((U < 0.0 && V > 0.0) || (U > 0.0 && V < 0.0)) return false;     // most misses end here
    const double W = exactSignDifferenceOfProducts(B.x, A.y, B.y, A.x);
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    const double det = U + V + W;
    if (det == 0.0) return false;
    hit.t = (U * A.z + V * B.z + W * C.z) / det;
    hit.u = V / det;
    hit.v = W / det;
    return true;
}

// Nearest root of |o + t d - c|^2 = r^2 in (tmin, tmax). The discriminant is formed as r^2 - |l|^2 with l
// the offset from the center to the closest point on the line (Haines et al. 2019, §7.2), which keeps it
// accurate for small spheres far away; the roots come from the cancellation-free pair c/q and q/a.
bool intersectSphere(const ObjectRay& ray, const dvec3& center, double radius, double& tHit) {
    const dvec3 f = ray.origin - center;
    const dvec3& d = ray.direction;
    const double a = glm::dot(d, d);
    if (a == 0.0) return false;
    const double beta = glm::dot(f, d);
    const dvec3 l = f - (beta / a) * d;
    const double r2 = radius * radius;
    const double disc = r2 - glm::dot(l, l);
    if (disc < 0.0) return false;
    const double c = glm::dot(f, f) - r2;
    const double q = -(beta + std::copysign(std::sqrt(a * disc), beta));
    double t0, t1;
    if (q == 0.0) {  // beta == 0 and disc == 0: origin on the surface, ray tangent to it
        t0 = t1 = 0.0;
    } else {
        t0 = c / q;
        t1 = q / a;
        if (t0 > t1) std::swap(t0, t1);
    }
    const double t = t0 > ray.tmin ? t0 : t1;
    if (!(t > ray.tmin && t < ray.tmax)) return false;
    tHit = t;
    return true;
}

struct CylinderHit {
    double t, axial, cap;
};

// Nearest hit in (tmin, tmax) of the round cylinder from a to b: the side solved as a circle across the
// unit axis w (the sphere quadratic on the components perpendicular to w) and kept between the ends, then
// the two cap disks when present.
bool intersectCylinder(const ObjectRay& ray, const dvec3& a, const dvec3& b, double radius, uint32_t caps, CylinderHit& hit) {
    const double length = glm::length(b - a);
    const dvec3 w = (b - a) / length;
    const dvec3 f = ray.origin - a;
    const double fa = glm::dot(f, w), da = glm::dot(ray.direction, w);
    const dvec3 fp = f - fa * w, dp = ray.direction - da * w;
    bool found = false;
    hit.t = ray.tmax;
    const double aa = glm::dot(dp, dp);
    if (aa > 0.0) {
        const double beta = glm::dot(fp, dp);
        const dvec3 l = fp - (beta / aa) * dp;
        const double disc = radius * radius - glm::dot(l, l);
        if (disc >= 0.0) {
            const double c = glm::dot(fp, fp) - radius * radius;
            const double q = -(beta + std::copysign(std::sqrt(aa * disc), beta));
            double roots[2] = {q == 0.0 ? 0.0 : c / q, q == 0.0 ? 0.0 : q / aa};
            if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
            for (double t : roots) {
                const double s = fa + t * da;
                if (t > ray.tmin && t < hit.t && s >= 0.0 && s <= length) {
                    hit = {t, s / length, 0.0};
                    found = true;
                    break;
                }
            }
        }
    }
    if (caps != 0 && da != 0.0) {
        for (int end = 0; end < 2; ++end) {
            if ((caps & (1u << end)) == 0) continue;  // CapEnds: bit 0 first, bit 1 second
            const double t = (end * length - fa) / da;
            const dvec3 across = fp + t * dp;
            if (t > ray.tmin && t < hit.t && glm::dot(across, across) <= radius * radius) {
                hit = {t, double(end), 1.0};
                found = true;
            }
        }
    }
    return found;
}

// Nearest hit of a cone frustum (a, ra) -> (b, rb) with the caps in `caps`, or with `round` of the two end
// spheres and the cone tangent to both: in double, the plain quadratic |fp + t dp| = r0 + k (fa + t da)
// without the GPU's re-centring (double has the digits to spare). Reports axial fraction and part as
// gpu::Hit (0 side, 1 cap, 2 end sphere).
bool intersectCone(const ObjectRay& ray, const dvec3& a, const dvec3& b, double ra, double rb, uint32_t caps, bool round,
                   CylinderHit& hit) {
    const double length = glm::length(b - a);
    const dvec3 w = (b - a) / length;
    bool found = false;
    hit.t = ray.tmax;
    if (round) {
        for (int end = 0; end < 2; ++end) {
            double t;
            if (!intersectSphere(ray, end == 0 ? a : b, end == 0 ? ra : rb, t) || !(t < hit.t)) continue;
            hit = {t, double(end), 2.0};
            found = true;
        }
    }
    double start = 0.0, stop = length, r0 = ra, r1 = rb;
    if (round) {
        const double sinAlpha = (rb - ra) / length;
        if (std::abs(sinAlpha) >= 1.0) return found;
        const double cosAlpha = std::sqrt(1.0 - sinAlpha * sinAlpha);
        start = -ra * sinAlpha;
        stop = length - rb * sinAlpha;
        r0 = ra * cosAlpha;
        r1 = rb * cosAlpha;
    }
    const double slope = (r1 - r0) / (stop - start);
    const dvec3 f = ray.origin - a;
    const double fa = glm::dot(f, w), da = glm::dot(ray.direction, w);
    const dvec3 fp = f - fa * w, dp = ray.direction - da * w;
    const double rf = r0 + slope * (fa - start);
    const double qa = glm::dot(dp, dp) - slope * slope * da * da;
    const double qb = glm::dot(fp, dp) - rf * slope * da;
    const double qc = glm::dot(fp, fp) - rf * rf;
    const double disc = qb * qb - qa * qc;
    if (disc >= 0.0) {
        const double q = -(qb + std::copysign(std::sqrt(disc), qb));
        const double roots[2] = {q != 0.0 ? qc / q : -1.0, qa != 0.0 ? q / qa : -1.0};
        for (double t : roots) {
            const double s = fa + t * da;
            if (t > ray.tmin && t < hit.t && s >= start && s <= stop && rf + slope * t * da >= 0.0) {
                hit = {t, s / length, 0.0};
                found = true;
            }
        }
    }
    if (!round && da != 0.0) {
        for (int end = 0; end < 2; ++end) {
            if ((caps & (1u << end)) == 0) continue;
            const double t = (end * length - fa) / da;
            const dvec3 across = fp + t * dp;
            const double r = end == 0 ? r0 : r1;
            if (t > ray.tmin && t < hit.t && glm::dot(across, across) <= r * r) {
                hit = {t, double(end), 1.0};
                found = true;
            }
        }
    }
    return found;
}

bool isRayUsable(const gpu::Ray& ray) {
    return isFinite(glm::vec3(ray.origin)) && isFinite(glm::vec3(ray.direction)) && std::isfinite(ray.origin.w) &&
           !std::isnan(ray.direction.w);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
// ReferenceScene

ReferenceScene::ReferenceScene(const core::SceneDescription& scene) {
    meshes_.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const core::TriangleMesh& mesh = scene.meshes[m];
        for (uint32_t t = 0; t < triangleCount(mesh); ++t) {
            if (!isTriangleValid(mesh, t)) continue;
            const glm::uvec3 idx = triangleIndices(mesh, t);
            meshes_[m].push_back({dvec3(mesh.positions[idx.x]), dvec3(mesh.positions[idx.y]),
                                  dvec3(mesh.positions[idx.z]), t});
        }
        validTriangles_ += meshes_[m].size();
    }
    sphereSets_.resize(scene.sphereSets.size());
    for (size_t s = 0; s < scene.sphereSets.size(); ++s) {
        const core::SphereSet& set = scene.sphereSets[s];
        for (uint32_t i = 0; i < sphereCount(set); ++i) {
            if (!isSphereValid(set, i)) continue;
            sphereSets_[s].push_back({dvec3(set.centers[i]), double(sphereRadius(set, i)), i});
        }
        validSpheres_ += sphereSets_[s].size();
    }
    cylinderSets_.resize(scene.cylinderSets.size());
    for (size_t s = 0; s < scene.cylinderSets.size(); ++s) {
        const core::CylinderSet& set = scene.cylinderSets[s];
        for (uint32_t i = 0; i < cylinderCount(set); ++i) {
            if (!isCylinderValid(set, i)) continue;
            const glm::uvec2 idx = cylinderIndices(set, i);
            cylinderSets_[s].push_back({dvec3(set.positions[idx.x]), dvec3(set.positions[idx.y]),
                                        double(cylinderRadius(set, i)), i, static_cast<uint32_t>(set.caps)});
        }
        validCylinders_ += cylinderSets_[s].size();
    }
    coneSets_.resize(scene.coneSets.size());
    for (size_t s = 0; s < scene.coneSets.size(); ++s) {
        const core::ConeSet& set = scene.coneSets[s];
        const auto prepared = core::prepareGeometry(set, bvh::BuildOptions{});  // the validity rules of core
        for (uint32_t i : prepared->validPrims) {
            const glm::uvec2 idx = core::coneIndices(set, i);
            coneSets_[s].push_back({dvec3(set.positions[idx.x]), dvec3(set.positions[idx.y]),
                                    double(core::radiusOf(set.radii, idx.x)), double(core::radiusOf(set.radii, idx.y)), i,
                                    static_cast<uint32_t>(set.caps), set.round});
        }
    }
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const core::InstanceDescription& inst = scene.instances[i];
        if (!isTransformValid(inst.transform)) continue;
        // Same rule as hasValidPrimitive, read from the already validated lists.
        const core::GeometryRef& g = inst.geometry;
        const bool nonEmpty =
            (g.kind == core::GeometryKind::Triangles && g.index < meshes_.size() && !meshes_[g.index].empty()) ||
            (g.kind == core::GeometryKind::Spheres && g.index < sphereSets_.size() && !sphereSets_[g.index].empty()) ||
            (g.kind == core::GeometryKind::Cylinders && g.index < cylinderSets_.size() && !cylinderSets_[g.index].empty()) ||
            (g.kind == core::GeometryKind::Cones && g.index < coneSets_.size() && !coneSets_[g.index].empty());
        if (!nonEmpty) continue;
        instances_.push_back({glm::inverse(glm::dmat3(inst.transform)), dvec3(inst.transform[3]), g.kind, g.index,
                              static_cast<uint32_t>(i)});
    }
}

// Calls visit(t, u, v, instanceId, primId) for every primitive hit in (tmin, tmax), in instance then
// primitive order; stops early when visit returns true.
template <typename Visit>
void ReferenceScene::forEachHit(const gpu::Ray& ray, Visit&& visit) const {
    if (!isRayUsable(ray)) return;
    const dvec3 worldOrigin(ray.origin);
    const dvec3 worldDirection(ray.direction);
    for (const Instance& inst : instances_) {
        const ObjectRay local{inst.worldToObject * (worldOrigin - inst.translation), inst.worldToObject * worldDirection,
                              double(ray.origin.w), double(ray.direction.w)};
        if (local.direction == dvec3(0.0)) continue;
        if (inst.kind == core::GeometryKind::Triangles) {
            const RayFrame frame(local.direction);
            for (const Triangle& tri : meshes_[inst.geometry]) {
                TriangleHit h;
                if (!intersectTriangle(local, frame, tri.a, tri.b, tri.c, h)) continue;
                if (!(h.t > local.tmin && h.t < local.tmax)) continue;
                if (visit(h.t, h.u, h.v, inst.instanceId, tri.primId)) return;
            }
        } else if (inst.kind == core::GeometryKind::Spheres) {
            for (const Sphere& sphere : sphereSets_[inst.geometry]) {
                double t;
                if (!intersectSphere(local, sphere.center, sphere.radius, t)) continue;
                if (visit(t, 0.0, 0.0, inst.instanceId, sphere.primId)) return;
            }
        } else if (inst.kind == core::GeometryKind::Cones) {
            for (const Cone& cone : coneSets_[inst.geometry]) {
                CylinderHit h;
                if (!intersectCone(local, cone.a, cone.b, cone.ra, cone.rb, cone.caps, cone.round, h)) continue;
                if (visit(h.t, h.axial, h.cap, inst.instanceId, cone.primId)) return;
            }
        } else {
            for (const Cylinder& cylinder : cylinderSets_[inst.geometry]) {
                CylinderHit h;
                if (!intersectCylinder(local, cylinder.a, cylinder.b, cylinder.radius, cylinder.caps, h)) continue;
                if (visit(h.t, h.axial, h.cap, inst.instanceId, cylinder.primId)) return;
            }
        }
    }
}

RefHit ReferenceScene::traceClosest(const gpu::Ray& ray) const {
    RefHit best;
    std::vector<double> hitTs;  // every hit, to count ties against the final nearest t
    forEachHit(ray, [&](double t, double u, double v, uint32_t instanceId, uint32_t primId) {
        hitTs.push_back(t);
        if (t < best.t) best = RefHit{true, t, instanceId, primId, u, v, 0};
        return false;
    });
    if (best.found) {
        const double tolerance = kTieRelativeTolerance * std::abs(best.t);
        best.hitCount = static_cast<int>(
            std::count_if(hitTs.begin(), hitTs.end(), [&](double t) { return std::abs(t - best.t) <= tolerance; }));
    }
    return best;
}

bool ReferenceScene::traceAny(const gpu::Ray& ray) const {
    bool hit = false;
    forEachHit(ray, [&](double, double, double, uint32_t, uint32_t) { return hit = true; });
    return hit;
}

std::vector<RefHit> ReferenceScene::traceClosest(std::span<const gpu::Ray> rays) const {
    std::vector<RefHit> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) hits[i] = traceClosest(rays[i]);
    });
    return hits;
}

std::vector<uint8_t> ReferenceScene::traceAny(std::span<const gpu::Ray> rays) const {
    std::vector<uint8_t> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) hits[i] = traceAny(rays[i]) ? 1 : 0;
    });
    return hits;
}

RefHit traceClosest(const core::SceneDescription& scene, const gpu::Ray& ray) {
    return ReferenceScene(scene).traceClosest(ray);
}

bool traceAny(const core::SceneDescription& scene, const gpu::Ray& ray) { return ReferenceScene(scene).traceAny(ray); }

std::vector<RefHit> traceClosestAll(const core::SceneDescription& scene, std::span<const gpu::Ray> rays) {
    return ReferenceScene(scene).traceClosest(rays);
}

std::vector<uint8_t> traceAnyAll(const core::SceneDescription& scene, std::span<const gpu::Ray> rays) {
    return ReferenceScene(scene).traceAny(rays);
}

}  // namespace ripple::test
