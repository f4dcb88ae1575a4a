// The bounds-culled ray exchange: each rank tells the others where its part of the scene lies (a few
// world boxes, core::Scene::regions()), and a ray travels only to the ranks whose boxes its segment enters,
// nearest first. A bounce takes two rounds: the first sends each ray to the nearest rank it enters; the
// second to every other rank it enters before the closest hit found so far. Rays carry only what tracing
// needs (36 bytes: origin, tmin, direction, the best t so far as tmax, slot); only hits, occlusion and
// unfinished traversals come back. A ray is left out only where no surface or volume of that rank can lie
// on its segment, so every ray finds the hit the ring exchange (and one rank) finds; only ties between
// ranks at exactly equal t may resolve to another rank (the nearer rank in ray order, then the lower
// rank), and volumes draw other random numbers (a visitor's are keyed by its slot in the batch traced).
#pragma once

#include "core/render/RayExchange.h"
#include "mpi/Communicator.h"

namespace ripple::mpi {

class BoundsExchange final : public core::RayExchange {
public:
    explicit BoundsExchange(Communicator communicator);

    uint32_t rank() const override { return uint32_t(communicator_.rank()); }
    uint32_t rankCount() const override { return uint32_t(communicator_.size()); }
    void shareRegions(std::span<const bvh::Aabb> mine) override;
    void exchangeClosest(std::vector<core::WireRay>& rays, core::RankTracer& tracer) override;
    void exchangeShadow(std::vector<core::WireShadowRay>& rays, core::RankTracer& tracer) override;
    uint64_t sum(uint64_t local) override { return communicator_.sum(local); }
    uint64_t max(uint64_t local) override { return communicator_.max(local); }
    core::ExchangeStats stats() const override { return stats_; }
    void resetStats() override { stats_ = {}; }

    const Communicator& communicator() const { return communicator_; }

private:
    // regionEntry into rank r's boxes, testing each run of kGroupSize boxes (siblings in the k-d split of
    // Scene::regions()) against their union first.
    static constexpr size_t kGroupSize = 8;
    float entryInto(const gpu::Ray& ray, float tmax, size_t rank) const;

    // One round: each rank sends the rays listed for each destination, traces what it receives and
    // answers; the answers are merged into `rays` in sender order.
    void visitClosest(std::vector<core::WireRay>& rays, const std::vector<std::vector<uint32_t>>& destinations,
                      core::RankTracer& tracer);

    Communicator communicator_;
    // Every rank's boxes as shared by the last shareRegions (this rank's own included), each grown by a
    // margin that covers float rounding in the entry test; indexed by rank.
    std::vector<std::vector<bvh::Aabb>> regions_;
    std::vector<std::vector<bvh::Aabb>> groups_;  // per rank: the union of each run of kGroupSize regions
    core::ExchangeStats stats_;
};

// The smallest t in [ray tmin, tmax] at which the ray enters any of `boxes`; +infinity where it enters
// none. A zero direction component tests the origin against the slab; NaN slab distances widen the
// interval (never cull a ray that might hit).
float regionEntry(const gpu::Ray& ray, float tmax, std::span<const bvh::Aabb> boxes);

}  // namespace ripple::mpi
