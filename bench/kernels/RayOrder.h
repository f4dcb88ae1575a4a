// Ray ordering for coherence (ripple-bench's --ray-order morton lever): rays sorted by a Morton code of
// their origin, then their direction octant, then a Morton code of their direction, so that neighbouring
// invocations of a trace kernel fetch the same BVH nodes.
#pragma once

#include "core/bvh/Aabb.h"
#include "shaders/shared/ray.h"

#include <cstdint>
#include <span>
#include <vector>

namespace ripple::bvh {

// 63-bit key: 30 bits of origin Morton code (10 bits per axis over `originBounds`), 3 bits of direction
// octant, 30 bits of Morton code of the unit direction over [-1, 1]^3. Rays from one point (a pinhole
// camera) are thus ordered by direction alone. Non-finite rays get the largest key.
uint64_t mortonRayKey(const gpu::Ray& ray, const Aabb& originBounds);

// The permutation that sorts `rays` by mortonRayKey (ties keep input order): order[i] is the input index
// of the i-th ray to trace. Results traced in that order go back with result[order[i]] = traced[i].
std::vector<uint32_t> mortonRayOrder(std::span<const gpu::Ray> rays);

template <class T>
std::vector<T> gatherInOrder(std::span<const T> items, std::span<const uint32_t> order) {
    std::vector<T> out(order.size());
    for (size_t i = 0; i < order.size(); ++i) out[i] = items[order[i]];
    return out;
}

template <class T>
std::vector<T> scatterFromOrder(std::span<const T> traced, std::span<const uint32_t> order) {
    std::vector<T> out(order.size());
    for (size_t i = 0; i < order.size(); ++i) out[order[i]] = traced[i];
    return out;
}

}  // namespace ripple::bvh
