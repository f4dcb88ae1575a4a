// Generates the benchmark's ray sets on the host, in parallel; both tracers then trace these same arrays.
#include "bench/ripple-bench/RaySets.h"

#include <glm/gtc/constants.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ripple::bench {

namespace {

uint32_t hash(uint32_t x) {  // a PCG output permutation: cheap and well mixed for per-ray streams
    const uint32_t state = x * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float unitFloat(uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }  // [0, 1)

glm::uvec3 triangle(const core::TriangleMesh& mesh, uint32_t prim) {
    return mesh.indices.empty() ? glm::uvec3(3 * prim, 3 * prim + 1, 3 * prim + 2) : mesh.indices[prim];
}

// Cosine-weighted direction about unit n: uniform disk point lifted to the hemisphere (Malley's method),
// in a frame built without branching on the normal's orientation (Duff et al. 2017).
glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const glm::vec3 s(b, sign + n.y * n.y * a, -n.y);
    const float r = std::sqrt(u1);
    const float phi = glm::two_pi<float>() * u2;
    const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
    return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * s + z * n);
}

}  // namespace

Bounds meshBounds(const core::TriangleMesh& mesh) {
    Bounds b;
    if (mesh.positions.empty()) return b;
    b.lo = b.hi = mesh.positions.front();
    for (const glm::vec3& p : mesh.positions) {
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
    }
    return b;
}

std::vector<gpu::Ray> primaryRays(const Bounds& bounds, uint32_t width, uint32_t height) {
    const glm::vec3 center = 0.5f * (bounds.lo + bounds.hi);
    const glm::vec3 forward = -glm::normalize(glm::vec3(0.35f, 0.3f, 1.0f));
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float halfHeight = std::tan(glm::radians(22.5f));
    const float halfWidth = halfHeight * float(width) / float(height);

    // The nearest eye distance from the centre at which all eight box corners are inside the frustum.
    float distance = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p(corner & 1 ? bounds.hi.x : bounds.lo.x, corner & 2 ? bounds.hi.y : bounds.lo.y,
                          corner & 4 ? bounds.hi.z : bounds.lo.z);
        const glm::vec3 q = p - center;
        const float depth = glm::dot(q, forward);
        distance = std::max({distance, std::abs(glm::dot(q, right)) / halfWidth - depth,
                             std::abs(glm::dot(q, up)) / halfHeight - depth});
    }
    const glm::vec3 eye = center - forward * std::max(distance, 1e-6f);

    std::vector<gpu::Ray> rays(size_t(width) * height);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height), [&](const auto& rowRange) {
        for (uint32_t y = rowRange.begin(); y != rowRange.end(); ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const float sx = (2.0f * (float(x) + 0.5f) / float(width) - 1.0f) * halfWidth;
                const float sy = (1.0f - 2.0f * (float(y) + 0.5f) / float(height)) * halfHeight;
                const glm::vec3 d = glm::normalize(forward + sx * right + sy * up);
                rays[size_t(y) * width + x] = gpu::Ray{glm::vec4(eye, 0.0f), glm::vec4(d, kRayFar)};
            }
        }
    });
    return rays;
}

glm::vec3 lightPosition(const Bounds& bounds) {
    const glm::vec3 center = 0.5f * (bounds.lo + bounds.hi);
    const glm::vec3 size = bounds.hi - bounds.lo;
    return glm::vec3(center.x + 0.2f * size.x, bounds.hi.y + 0.25f * bounds.diagonal(), center.z + 0.1f * size.z);
}

SecondaryRays secondaryRays(const core::TriangleMesh& mesh, const Bounds& bounds, std::span<const gpu::Ray> primary,
                            std::span<const gpu::Hit> hits, uint32_t seed) {
    SecondaryRays out;
    const size_t triangleCount = mesh.indices.empty() ? mesh.positions.size() / 3 : mesh.indices.size();
    for (uint32_t i = 0; i < uint32_t(primary.size()); ++i)  // primId is checked: the hits may be Ripple's
        if (hits[i].status == gpu::HIT_FOUND && hits[i].primId < triangleCount) out.source.push_back(i);
    out.shadow.resize(out.source.size());
    out.bounce.resize(out.source.size());

    const glm::vec3 light = lightPosition(bounds);
    const float offset = kOffsetRelative * bounds.diagonal();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.source.size(), 1024), [&](const auto& range) {
        for (size_t k = range.begin(); k != range.end(); ++k) {
            const uint32_t i = out.source[k];
            const gpu::Hit& h = hits[i];
            const glm::uvec3 tri = triangle(mesh, h.primId);
            const glm::vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y], p2 = mesh.positions[tri.z];
            // Barycentrics put the point on the triangle; o + t d would sit above or below it by t's rounding.
            const glm::vec3 p = (1.0f - h.u - h.v) * p0 + h.u * p1 + h.v * p2;
            const glm::vec3 incoming(primary[i].direction);
            const glm::vec3 c = glm::cross(p1 - p0, p2 - p0);
            const float twiceArea = glm::length(c);
            // A sliver can be hit yet have no representable normal; facing the ray keeps its rays defined.
            glm::vec3 n = twiceArea > 0.0f && std::isfinite(twiceArea) ? c / twiceArea : -glm::normalize(incoming);
            if (glm::dot(n, incoming) > 0.0f) n = -n;  // the side the primary ray came from
            const glm::vec3 origin = p + offset * n;

            out.shadow[k] = gpu::Ray{glm::vec4(origin, 0.0f), glm::vec4(light - origin, 1.0f)};
            const uint32_t r0 = hash(i ^ hash(seed));
            const uint32_t r1 = hash(r0);
            const glm::vec3 d = cosineDirection(n, unitFloat(r0), unitFloat(r1));
            out.bounce[k] = gpu::Ray{glm::vec4(origin, 0.0f), glm::vec4(d, kRayFar)};
        }
    });
    return out;
}

}  // namespace ripple::bench
