// How the wavefront loop meets the other ranks of a data-parallel render, without knowing MPI: after the
// local closest-hit and any-hit traces it hands its queue to a RayExchange, which returns every ray with
// the globally closest hit (and the SurfaceRecord packed by the rank that owns it) or occlusion. Local is
// the one-rank exchange; mpi/RingExchange cycles the queues through all ranks; mpi/BoundsExchange sends each
// ray only to the ranks whose world boxes it enters.
#pragma once

#include "core/bvh/Aabb.h"
#include "shaders/shared/path.h"
#include "shaders/shared/ray.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace ripple::core {

// A path ray as it crosses ranks: what tracing it needs and the closest hit found so far, never the path
// state (throughput, pixel, depth stay at home). record.status and record.position.w are the best hit's
// status and t.
struct WireRay {
    gpu::Ray ray;               // origin (w: tmin), direction (w: the ray's own tmax)
    uint32_t homeRank = 0;
    uint32_t id = 0;            // index in the home rank's queue
    uint32_t pad0 = 0;
    uint32_t pad1 = 0;
    gpu::SurfaceRecord record;  // packed by the rank that owns the closest hit so far
};
static_assert(sizeof(WireRay) == sizeof(gpu::Ray) + 16 + sizeof(gpu::SurfaceRecord));

// A shadow ray as it crosses ranks; occlusion is HIT_MISS or HIT_FOUND (occluded by some rank so far),
// with HIT_FLAG_* bits where a traversal could not finish; transmittance is the product over the ranks so
// far of their volumes' transmittance along it (1 without volumes).
struct WireShadowRay {
    gpu::Ray ray;
    uint32_t homeRank = 0;
    uint32_t id = 0;
    uint32_t occlusion = 0;
    float transmittance = 1.0f;
};
static_assert(sizeof(WireShadowRay) == 48);

// How a rank's answer updates what a ray carries, the same for every exchange. HIT_FLAG_* bits (above the
// low byte) say a traversal could not finish somewhere: they stay set whatever is found elsewhere.
inline constexpr uint32_t kHitStatusFlags = ~0xFFu;

// `found` is a closer hit: it replaces the carried record, keeping the carried flags.
inline void takeCloserHit(gpu::SurfaceRecord& carried, const gpu::SurfaceRecord& found) {
    const uint32_t flags = carried.status & kHitStatusFlags;
    carried = found;
    carried.status |= flags;
}

// Occluded by any rank is occluded, even where another rank could not finish its traversal.
inline uint32_t mergeOcclusion(uint32_t carried, uint32_t found) {
    return (found & 0xFFu) == gpu::HIT_FOUND ? gpu::HIT_FOUND : carried | (found & kHitStatusFlags);
}

// What a rank does to rays visiting from another rank: trace them against its own part of the scene.
class RankTracer {
public:
    virtual ~RankTracer() = default;
    // Replaces each ray's record where this rank has a closer hit than record.position.w (or any hit, where
    // the record is a miss), packing the record here, where the surface's data lives.
    virtual void traceClosest(std::span<WireRay> rays) = 0;
    // Sets occlusion to HIT_FOUND where this rank occludes a ray that is not yet occluded, and multiplies
    // the transmittance of the others by that of this rank's volumes.
    virtual void traceShadow(std::span<WireShadowRay> rays) = 0;
};

// Traffic of one rank, summed over a frame.
struct ExchangeStats {
    uint64_t raysSent = 0;      // path and shadow rays this rank sent to another rank, each hop counted
    uint64_t bytesSent = 0;     // rays and their answers (hits, occlusion) sent to other ranks
    uint64_t raysReceived = 0;  // rays of other ranks traced here
    uint64_t visitMicroseconds = 0;  // spent tracing them (the RankTracer's calls)
    uint64_t regionBytes = 0;   // world boxes sent to other ranks (BoundsExchange, once per frame)
    uint64_t hops = 0;          // rounds of sending (ring: hops; bounds: rounds)
};

// The exchanges a data-parallel render can use (the device parameter "rayExchange").
enum class ExchangeKind : uint32_t { Bounds, Ring };
inline constexpr const char* kExchangeNames = "\"bounds\", \"ring\"";
std::optional<ExchangeKind> parseExchangeKind(std::string_view name);
const char* exchangeKindName(ExchangeKind kind);

class RayExchange {
public:
    virtual ~RayExchange() = default;
    virtual uint32_t rank() const = 0;
    virtual uint32_t rankCount() const = 0;
    // Collective, before a frame's first exchange: this rank's world boxes (Scene::regions()). Exchanges
    // that route rays by them gather every rank's; the others ignore them.
    virtual void shareRegions(std::span<const bvh::Aabb> mine) { (void)mine; }
    // On entry: this rank's queue after its local trace. On return: every ray has met every rank's part.
    virtual void exchangeClosest(std::vector<WireRay>& rays, RankTracer& tracer) = 0;
    virtual void exchangeShadow(std::vector<WireShadowRay>& rays, RankTracer& tracer) = 0;
    // Sum and maximum over all ranks: every rank must call these the same number of times.
    virtual uint64_t sum(uint64_t local) = 0;
    virtual uint64_t max(uint64_t local) = 0;
    virtual ExchangeStats stats() const { return {}; }
    virtual void resetStats() {}
};

// One rank holds the whole scene: the local trace is already the global one.
class LocalRayExchange final : public RayExchange {
public:
    uint32_t rank() const override { return 0; }
    uint32_t rankCount() const override { return 1; }
    void exchangeClosest(std::vector<WireRay>&, RankTracer&) override {}
    void exchangeShadow(std::vector<WireShadowRay>&, RankTracer&) override {}
    uint64_t sum(uint64_t local) override { return local; }
    uint64_t max(uint64_t local) override { return local; }
};

}  // namespace ripple::core
