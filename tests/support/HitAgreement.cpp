// Classification of GPU closest hits against the reference (see HitAgreement.h for the tolerances).
#include "tests/support/HitAgreement.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ripple::test {

namespace {

struct SurfacePoint {
    double cosine = 1.0;
    double kappa = 1.0;
    double edgeGap = std::numeric_limits<double>::infinity();  // ray to nearest edge or silhouette
    double scale = 1.0;
};

// Distance between the line o + s*d and the segment [a, b].
double lineSegmentDistance(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 e = b - a, w = a - o;
    const double dd = glm::dot(d, d), ee = glm::dot(e, e), de = glm::dot(d, e);
    const double denom = dd * ee - de * de;
    double u = denom > 1e-300 ? (de * glm::dot(d, w) - dd * glm::dot(e, w)) / denom : 0.0;  // along the segment
    u = std::clamp(u, 0.0, 1.0);
    const glm::dvec3 q = a + u * e;
    const glm::dvec3 r = q - o;
    return glm::length(r - (glm::dot(r, d) / dd) * d);
}

SurfacePoint surfacePoint(const core::SceneDescription& desc, uint32_t instanceId, uint32_t primId, const gpu::Ray& ray, double t) {
    const glm::dvec3 o(ray.origin), dir(ray.direction);
    const glm::dvec3 p = o + t * dir;
    SurfacePoint sp;
    sp.scale = std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z), std::abs(o.x), std::abs(o.y), std::abs(o.z)});
    const core::InstanceDescription& inst = desc.instances[instanceId];
    const glm::dmat4 m(inst.transform);
    if (inst.geometry.kind == core::GeometryKind::Triangles) {
        const core::TriangleMesh& mesh = desc.meshes[inst.geometry.index];
        const glm::uvec3 idx = triangleIndices(mesh, primId);
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions[idx[k]]), 1.0));
        const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
        sp.cosine = std::abs(glm::dot(glm::normalize(n), glm::normalize(dir)));
        double longest = 0.0;
        for (int k = 0; k < 3; ++k) {
            longest = std::max(longest, glm::length(v[(k + 1) % 3] - v[k]));
            sp.edgeGap = std::min(sp.edgeGap, lineSegmentDistance(o, dir, v[k], v[(k + 1) % 3]));
        }
        sp.kappa = longest * longest / glm::length(n);
    } else if (inst.geometry.kind == core::GeometryKind::Cylinders) {
        // In object space: the normal at the hit, the gap between the ray and the side's silhouette
        // (line-to-axis distance against the radius) and between the hit and the nearer end rim.
        const core::CylinderSet& set = desc.cylinderSets[inst.geometry.index];
        const glm::dmat4 inv = glm::inverse(m);
        const glm::uvec2 idx = cylinderIndices(set, primId);
        const glm::dvec3 a(set.positions[idx.x]), b(set.positions[idx.y]);
        const double r = cylinderRadius(set, primId);
        const double length = glm::length(b - a);
        const glm::dvec3 w = (b - a) / length;
        const glm::dvec3 oObject = glm::dvec3(inv * glm::dvec4(o, 1.0)), dObject = glm::dmat3(inv) * dir;
        const glm::dvec3 q = glm::dvec3(inv * glm::dvec4(p, 1.0)) - a;
        const double s = glm::dot(q, w);
        const glm::dvec3 radial = q - s * w;
        const double rho = glm::length(radial);
        const bool onCap = set.caps != core::CapEnds::None && (s <= 0.0 || s >= length || std::abs(rho) < r * (1.0 - 1e-6));
        const glm::dvec3 nObject = onCap ? (s < 0.5 * length ? -w : w) : radial / std::max(rho, 1e-300);
        const glm::dvec3 n = glm::normalize(glm::transpose(glm::dmat3(inv)) * nObject);
        sp.cosine = std::abs(glm::dot(n, glm::normalize(dir)));
        const glm::dvec3 cross = glm::cross(dObject, w);
        const glm::dvec3 f = oObject - a;
        const double axisDistance = glm::length(cross) > 0.0 ? std::abs(glm::dot(f, cross)) / glm::length(cross)
                                                               : glm::length(f - glm::dot(f, w) * w);
        const double stretch = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
        const double endGap = std::min(std::abs(s), std::abs(length - s));
        const double rimGap = std::sqrt(endGap * endGap + (rho - r) * (rho - r));
        sp.edgeGap = std::min(std::abs(axisDistance - r), rimGap) * stretch;
    } else {
        const core::SphereSet& set = desc.sphereSets[inst.geometry.index];
        const glm::dmat4 inv = glm::inverse(m);
        const glm::dvec3 c(set.centers[primId]);
        const glm::dvec3 oObject = glm::dvec3(inv * glm::dvec4(o, 1.0)), dObject = glm::dmat3(inv) * dir;
        const glm::dvec3 n = glm::normalize(glm::transpose(glm::dmat3(inv)) * (glm::dvec3(inv * glm::dvec4(p, 1.0)) - c));
        sp.cosine = std::abs(glm::dot(n, glm::normalize(dir)));
        const glm::dvec3 r = c - oObject;
        const double centerDistance = glm::length(r - (glm::dot(r, dObject) / glm::dot(dObject, dObject)) * dObject);
        const double stretch = std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
        sp.edgeGap = std::abs(double(sphereRadius(set, primId)) - centerDistance) * stretch;
    }
    return sp;
}

}  // namespace

Agreement compareClosest(const core::SceneDescription& d, std::span<const gpu::Ray> rays,
                         std::span<const gpu::Hit> gpuHits, std::span<const RefHit> ref) {
    Agreement a;
    for (size_t i = 0; i < rays.size(); ++i) {
        const gpu::Hit& g = gpuHits[i];
        const RefHit& r = ref[i];
        if ((g.status & ~0xFFu) != 0) { ++a.flagged; continue; }
        const bool gpuFound = g.status == gpu::HIT_FOUND;
        if (!gpuFound && !r.found) { ++a.exact; continue; }
        const double dirLength = glm::length(glm::dvec3(rays[i].direction));
        auto tTolerance = [&](const SurfacePoint& sp) {
            return 1e-6 * sp.scale * sp.kappa / (dirLength * std::max(sp.cosine, 1e-3));
        };
        auto nearEdge = [&](const SurfacePoint& sp) { return sp.edgeGap <= 4e-6 * sp.scale; };
        const SurfacePoint refPoint = r.found ? surfacePoint(d, r.instanceId, r.primId, rays[i], r.t) : SurfacePoint{};
        const SurfacePoint gpuPoint = gpuFound ? surfacePoint(d, g.instanceId, g.primId, rays[i], g.t) : SurfacePoint{};
        if (gpuFound && r.found && std::abs(double(g.t) - r.t) <= tTolerance(refPoint)) {
            if (g.instanceId == r.instanceId && g.primId == r.primId) ++a.exact;
            else ++a.ties;
        } else if (gpuFound && r.found && r.hitCount > 1 && g.instanceId == r.instanceId && g.primId != r.primId &&
                   std::abs(double(g.t) - r.t) <= tTolerance(gpuPoint)) {
            ++a.ties;
        } else if ((r.found && nearEdge(refPoint)) || (gpuFound && nearEdge(gpuPoint))) {
            ++a.edges;
        } else {
            ++a.wrong;
        }
    }
    return a;
}

}  // namespace ripple::test
