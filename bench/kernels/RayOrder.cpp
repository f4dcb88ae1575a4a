// Morton-code ray ordering (see RayOrder.h). Keys are computed in parallel and (key, index) pairs sorted, a
// total order, so equal keys keep input order and the permutation is deterministic.
#include "bench/kernels/RayOrder.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace ripple::bvh {

namespace {

// Spreads the low 10 bits of v so that two zero bits follow each (bit i moves to bit 3i).
uint64_t spreadBits(uint32_t v) {
    uint64_t x = v & 0x3FFu;
    x = (x | (x << 16)) & 0x30000FFull;
    x = (x | (x << 8)) & 0x300F00Full;
    x = (x | (x << 4)) & 0x30C30C3ull;
    x = (x | (x << 2)) & 0x9249249ull;
    return x;
}

uint32_t quantize(float value, float lo, float hi) {
    const float extent = hi - lo;
    const float unit = extent > 0.0f ? (value - lo) / extent : 0.0f;
    return static_cast<uint32_t>(std::clamp(unit, 0.0f, 1.0f) * 1023.0f);
}

uint64_t morton(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return spreadBits(quantize(p.x, lo.x, hi.x)) | spreadBits(quantize(p.y, lo.y, hi.y)) << 1 |
           spreadBits(quantize(p.z, lo.z, hi.z)) << 2;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

uint64_t mortonRayKey(const gpu::Ray& ray, const Aabb& originBounds) {
    const glm::vec3 origin(ray.origin);
    const glm::vec3 direction(ray.direction);
    const float length = glm::length(direction);
    if (!finite(origin) || !finite(direction) || !(length > 0.0f) || !std::isfinite(length))
        return (uint64_t(1) << 63) - 1;
    const glm::vec3 unit = direction / length;
    const uint64_t octant = uint64_t(unit.x < 0.0f) | uint64_t(unit.y < 0.0f) << 1 | uint64_t(unit.z < 0.0f) << 2;
    return morton(origin, originBounds.lo, originBounds.hi) << 33 | octant << 30 |
           morton(unit, glm::vec3(-1.0f), glm::vec3(1.0f));
}

std::vector<uint32_t> mortonRayOrder(std::span<const gpu::Ray> rays) {
    Aabb bounds;
    for (const gpu::Ray& ray : rays)
        if (finite(glm::vec3(ray.origin))) bounds.extend(glm::vec3(ray.origin));
    std::vector<std::pair<uint64_t, uint32_t>> keyed(rays.size());
    tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) {
        keyed[i] = {mortonRayKey(rays[i], bounds), static_cast<uint32_t>(i)};
    });
    // Pairs compare by key, then by index: a total order, so the parallel sort is deterministic.
    tbb::parallel_sort(keyed.begin(), keyed.end());
    std::vector<uint32_t> order(rays.size());
    for (size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
    return order;
}

}  // namespace ripple::bvh
