// Bounds-culled exchange (see BoundsExchange.h). Wire formats, all little-endian as the ranks share one
// architecture: a visiting ray is gpu::Ray (32 bytes, direction.w = best t so far) and its slot in the
// sender's queue (4); a closest-hit answer is the slot (4) and the gpu::SurfaceRecord packed here (128),
// sent only for a hit or an unfinished traversal; a shadow answer is the slot, occlusion and
// transmittance (12), sent only where occluded, dimmed or unfinished.
#include "mpi/BoundsExchange.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstring>
#include <limits>
#include <string>

// The entry test is compiled for AVX-512 and AVX2 as well, chosen when the library loads (16 boxes a
// step on this project's CPUs instead of SSE's 4).
#if defined(__x86_64__) && defined(__GNUC__)
#define RIPPLE_WIDE_SIMD __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define RIPPLE_WIDE_SIMD
#endif

namespace ripple::mpi {

namespace {

constexpr size_t kVisitorBytes = sizeof(gpu::Ray) + sizeof(uint32_t);
constexpr size_t kHitAnswerBytes = sizeof(uint32_t) + sizeof(gpu::SurfaceRecord);
constexpr size_t kShadowAnswerBytes = 3 * sizeof(uint32_t);
static_assert(sizeof(gpu::Ray) == 32 && sizeof(gpu::SurfaceRecord) == 128);

template <class T>
void append(std::vector<uint8_t>& bytes, const T& value) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &value, sizeof(T));
}

template <class T>
T read(const std::vector<uint8_t>& bytes, size_t at) {
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    return value;
}

uint64_t microsecondsSince(std::chrono::steady_clock::time_point start) {
    return uint64_t(
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start).count());
}

float bestT(const core::WireRay& ray) {
    return (ray.record.status & 0xFFu) == gpu::HIT_FOUND ? std::min(ray.record.position.w, ray.ray.direction.w)
                                                        : ray.ray.direction.w;
}

void checkWhole(const std::vector<uint8_t>& bytes, size_t itemBytes, int sender, const char* what) {
    if (bytes.size() % itemBytes != 0)
        throw MpiError("ray exchange: rank " + std::to_string(sender) + " sent " + std::to_string(bytes.size()) +
                       " bytes, not whole " + what);
}

uint32_t checkedSlot(uint32_t slot, size_t count, int sender) {
    if (slot >= count)
        throw MpiError("ray exchange: rank " + std::to_string(sender) + " answered for slot " + std::to_string(slot) +
                       " of a queue of " + std::to_string(count));
    return slot;
}

// The rays of `destinations[r]`, each with tmax = `tmaxOf(slot)`, as bytes for rank r.
template <class Items, class TMax>
std::vector<std::vector<uint8_t>> packVisitors(const Items& items, const std::vector<std::vector<uint32_t>>& destinations,
                                               TMax tmaxOf) {
    std::vector<std::vector<uint8_t>> outgoing(destinations.size());
    for (size_t r = 0; r < destinations.size(); ++r) {
        outgoing[r].reserve(destinations[r].size() * kVisitorBytes);
        for (uint32_t slot : destinations[r]) {
            gpu::Ray ray = items[slot].ray;
            ray.direction.w = tmaxOf(slot);
            append(outgoing[r], ray);
            append(outgoing[r], slot);
        }
    }
    return outgoing;
}

// Sends each rank the rays listed for it (tmax = tmaxOf(slot)) and returns every sender's rays, as
// visitors in sender order (homeRank: the sender; id: the slot there; the rest as a fresh Item).
template <class Item, class Items, class TMax>
std::vector<Item> sendVisitors(const Communicator& communicator, const Items& items,
                               const std::vector<std::vector<uint32_t>>& destinations, TMax tmaxOf,
                               core::ExchangeStats& stats) {
    const std::vector<std::vector<uint8_t>> outgoing = packVisitors(items, destinations, tmaxOf);
    for (size_t r = 0; r < destinations.size(); ++r) {
        stats.raysSent += destinations[r].size();
        stats.bytesSent += outgoing[r].size();
    }
    ++stats.hops;
    const std::vector<std::vector<uint8_t>> received = communicator.alltoallv(outgoing);
    std::vector<Item> visitors;
    for (size_t s = 0; s < received.size(); ++s) {
        checkWhole(received[s], kVisitorBytes, int(s), "rays");
        for (size_t at = 0; at < received[s].size(); at += kVisitorBytes) {
            Item visitor{};
            visitor.ray = read<gpu::Ray>(received[s], at);
            visitor.homeRank = uint32_t(s);
            visitor.id = read<uint32_t>(received[s], at + sizeof(gpu::Ray));
            visitors.push_back(visitor);
        }
    }
    stats.raysReceived += visitors.size();
    return visitors;
}

// RegionBoxes::entry over `count` boxes given by their bounds per axis.
RIPPLE_WIDE_SIMD float nearestEntry(const float* const (&lo)[3], const float* const (&hi)[3], size_t count,
                                    const gpu::Ray& ray, float tmax) {
    // With 1 / d, a zero component gives infinite slab distances of the origin's side (the ray misses the
    // slab) or, for an origin on a face, 0 * infinity = NaN (kept, as on the face). The reciprocal rounds
    // once more than a division, well inside the 1e-6 widening.
    float origin[3], inverse[3];
    for (int a = 0; a < 3; ++a) {
        origin[a] = ray.origin[a];
        inverse[a] = 1.0f / ray.direction[a];
    }
    constexpr float kEarlier = 1.0f - 1e-6f, kLater = 1.0f + 1e-6f;
    const float tmin = ray.origin.w;
    float nearest = std::numeric_limits<float>::infinity();
    // Chunks of boxes: the entries of a chunk are computed without branches (the compiler runs that loop
    // across boxes), then their minimum is taken.
    constexpr size_t kChunk = 16;
    float entries[kChunk];
    for (size_t first = 0; first < count; first += kChunk) {
        const size_t chunk = std::min(kChunk, count - first);
        for (size_t k = 0; k < chunk; ++k) {
            const size_t i = first + k;
            float t0 = tmin, t1 = tmax;
            for (int a = 0; a < 3; ++a) {
                const float toLo = (lo[a][i] - origin[a]) * inverse[a], toHi = (hi[a][i] - origin[a]) * inverse[a];
                // Ordered as the two compare, so a NaN stays where it was and leaves its bound as it was.
                const float near0 = toLo > toHi ? toHi : toLo, far0 = toLo > toHi ? toLo : toHi;
                // Widened by a scale, not a difference, so an infinite distance stays infinite.
                const float near = near0 * (near0 > 0.0f ? kEarlier : kLater);
                const float far = far0 * (far0 > 0.0f ? kLater : kEarlier);
                t0 = near > t0 ? near : t0;
                t1 = far < t1 ? far : t1;
            }
            entries[k] = t0 <= t1 ? t0 : std::numeric_limits<float>::infinity();
        }
        for (size_t k = 0; k < chunk; ++k) nearest = std::min(nearest, entries[k]);
    }
    return nearest;
}

}  // namespace

void RegionBoxes::add(const bvh::Aabb& box) {
    for (int a = 0; a < 3; ++a) {
        lo_[a].push_back(box.lo[a]);
        hi_[a].push_back(box.hi[a]);
    }
}

float RegionBoxes::entry(const gpu::Ray& ray, float tmax) const {
    const float* const lo[3] = {lo_[0].data(), lo_[1].data(), lo_[2].data()};
    const float* const hi[3] = {hi_[0].data(), hi_[1].data(), hi_[2].data()};
    return nearestEntry(lo, hi, size(), ray, tmax);
}

BoundsExchange::BoundsExchange(Communicator communicator) : communicator_(std::move(communicator)) {}

void BoundsExchange::shareRegions(std::span<const bvh::Aabb> mine) {
    std::vector<uint8_t> bytes;
    for (const bvh::Aabb& box : mine) {
        append(bytes, box.lo);
        append(bytes, box.hi);
    }
    const std::vector<std::vector<uint8_t>> all = communicator_.allgather(bytes);
    stats_.regionBytes += bytes.size() * size_t(std::max(0, communicator_.size() - 1));
    regions_.assign(all.size(), {});
    for (size_t r = 0; r < all.size(); ++r) {
        checkWhole(all[r], 2 * sizeof(glm::vec3), int(r), "boxes");
        for (size_t at = 0; at < all[r].size(); at += 2 * sizeof(glm::vec3)) {
            bvh::Aabb box{read<glm::vec3>(all[r], at), read<glm::vec3>(all[r], at + sizeof(glm::vec3))};
            if (box.empty()) continue;
            // Float rounding in the entry test and in the owner's traversal: grow by a relative margin.
            const glm::vec3 magnitude = glm::max(glm::abs(box.lo), glm::abs(box.hi));
            const float margin = 1e-4f * glm::length(box.hi - box.lo) +
                                 1e-5f * std::max({magnitude.x, magnitude.y, magnitude.z}) + 1e-30f;
            box.lo -= margin;
            box.hi += margin;
            regions_[r].add(box);
        }
    }
}

void BoundsExchange::visitClosest(std::vector<core::WireRay>& rays,
                                  const std::vector<std::vector<uint32_t>>& destinations, core::RankTracer& tracer) {
    const int ranks = communicator_.size();
    // Every sender's visitors in one batch, traced here; their record is a miss, so the ray's own tmax
    // (the best t at home) bounds the trace.
    std::vector<core::WireRay> visitors = sendVisitors<core::WireRay>(
        communicator_, rays, destinations, [&](uint32_t slot) { return bestT(rays[slot]); }, stats_);
    const auto start = std::chrono::steady_clock::now();
    tracer.traceClosest(visitors);
    stats_.visitMicroseconds += microsecondsSince(start);
    std::vector<std::vector<uint8_t>> answers(static_cast<size_t>(ranks));
    for (const core::WireRay& visitor : visitors) {
        if (visitor.record.status == gpu::HIT_MISS) continue;
        std::vector<uint8_t>& bytes = answers[visitor.homeRank];
        append(bytes, visitor.id);
        append(bytes, visitor.record);
    }
    for (int r = 0; r < ranks; ++r) stats_.bytesSent += answers[size_t(r)].size();
    const std::vector<std::vector<uint8_t>> returned = communicator_.alltoallv(answers);

    // In sender order, so ties between ranks resolve the same way on every run.
    for (int s = 0; s < ranks; ++s) {
        checkWhole(returned[size_t(s)], kHitAnswerBytes, s, "answers");
        for (size_t at = 0; at < returned[size_t(s)].size(); at += kHitAnswerBytes) {
            const uint32_t slot = checkedSlot(read<uint32_t>(returned[size_t(s)], at), rays.size(), s);
            const auto found = read<gpu::SurfaceRecord>(returned[size_t(s)], at + sizeof(uint32_t));
            gpu::SurfaceRecord& carried = rays[slot].record;
            const bool closer = (found.status & 0xFFu) == gpu::HIT_FOUND &&
                                ((carried.status & 0xFFu) != gpu::HIT_FOUND || found.position.w < carried.position.w);
            if (closer) core::takeCloserHit(carried, found);
            else carried.status |= found.status & core::kHitStatusFlags;
        }
    }
}

void BoundsExchange::exchangeClosest(std::vector<core::WireRay>& rays, core::RankTracer& tracer) {
    const int ranks = communicator_.size();
    if (ranks <= 1) return;
    if (regions_.size() != size_t(ranks))
        throw MpiError("ray exchange: shareRegions was not called before the bounds exchange");
    // Each ray's candidate ranks: those whose boxes its segment enters before its best hit, nearest first.
    struct Candidate {
        float entry;
        uint32_t rank;
        bool operator<(const Candidate& o) const { return entry < o.entry || (entry == o.entry && rank < o.rank); }
    };
    std::vector<Candidate> candidates;
    std::vector<uint32_t> firstCandidate(rays.size() + 1, 0);
    for (size_t i = 0; i < rays.size(); ++i) {
        const size_t begin = candidates.size();
        const float best = bestT(rays[i]);
        for (int r = 0; r < ranks; ++r) {
            if (r == communicator_.rank()) continue;
            const float entry = regions_[size_t(r)].entry(rays[i].ray, best);
            if (std::isfinite(entry) && entry <= best) candidates.push_back({entry, uint32_t(r)});
        }
        std::sort(candidates.begin() + long(begin), candidates.end());
        firstCandidate[i + 1] = uint32_t(candidates.size());
    }
    std::vector<std::vector<uint32_t>> destinations(static_cast<size_t>(ranks));
    // Round 1: the nearest rank each ray enters.
    for (size_t i = 0; i < rays.size(); ++i)
        if (firstCandidate[i] < firstCandidate[i + 1]) destinations[candidates[firstCandidate[i]].rank].push_back(uint32_t(i));
    visitClosest(rays, destinations, tracer);
    // Round 2: every other rank the ray enters before the closest hit found so far.
    for (auto& list : destinations) list.clear();
    for (size_t i = 0; i < rays.size(); ++i) {
        const float best = bestT(rays[i]);
        for (uint32_t k = firstCandidate[i] + 1; k < firstCandidate[i + 1]; ++k)
            if (candidates[k].entry <= best) destinations[candidates[k].rank].push_back(uint32_t(i));
    }
    visitClosest(rays, destinations, tracer);
}

// One round: a shadow ray needs every rank it enters (occlusion anywhere is occlusion), and the answers
// commute, so all go at once.
void BoundsExchange::exchangeShadow(std::vector<core::WireShadowRay>& rays, core::RankTracer& tracer) {
    const int ranks = communicator_.size();
    if (ranks <= 1) return;
    if (regions_.size() != size_t(ranks))
        throw MpiError("ray exchange: shareRegions was not called before the bounds exchange");
    std::vector<std::vector<uint32_t>> destinations(static_cast<size_t>(ranks));
    for (size_t i = 0; i < rays.size(); ++i) {
        if ((rays[i].occlusion & 0xFFu) == gpu::HIT_FOUND) continue;  // settled at home
        for (int r = 0; r < ranks; ++r)
            if (r != communicator_.rank() &&
                std::isfinite(regions_[size_t(r)].entry(rays[i].ray, rays[i].ray.direction.w)))
                destinations[size_t(r)].push_back(uint32_t(i));
    }
    // Unoccluded (HIT_MISS) and undimmed (transmittance 1) as they arrive.
    std::vector<core::WireShadowRay> visitors = sendVisitors<core::WireShadowRay>(
        communicator_, rays, destinations, [&](uint32_t slot) { return rays[slot].ray.direction.w; }, stats_);
    const auto start = std::chrono::steady_clock::now();
    tracer.traceShadow(visitors);
    stats_.visitMicroseconds += microsecondsSince(start);
    std::vector<std::vector<uint8_t>> answers(static_cast<size_t>(ranks));
    for (const core::WireShadowRay& visitor : visitors) {
        if (visitor.occlusion == gpu::HIT_MISS && visitor.transmittance == 1.0f) continue;
        std::vector<uint8_t>& bytes = answers[visitor.homeRank];
        append(bytes, visitor.id);
        append(bytes, visitor.occlusion);
        append(bytes, visitor.transmittance);
    }
    for (int r = 0; r < ranks; ++r) stats_.bytesSent += answers[size_t(r)].size();
    const std::vector<std::vector<uint8_t>> returned = communicator_.alltoallv(answers);
    for (int s = 0; s < ranks; ++s) {
        checkWhole(returned[size_t(s)], kShadowAnswerBytes, s, "shadow answers");
        for (size_t at = 0; at < returned[size_t(s)].size(); at += kShadowAnswerBytes) {
            const uint32_t slot = checkedSlot(read<uint32_t>(returned[size_t(s)], at), rays.size(), s);
            core::WireShadowRay& carried = rays[slot];
            carried.occlusion = core::mergeOcclusion(carried.occlusion, read<uint32_t>(returned[size_t(s)], at + 4));
            carried.transmittance *= read<float>(returned[size_t(s)], at + 8);
        }
    }
}

}  // namespace ripple::mpi
