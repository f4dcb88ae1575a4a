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

// World boxes laid out for the entry test: one array per axis and bound, so the test of a ray runs across
// the boxes in SIMD lanes (the exchange tests every ray against every other rank's boxes, twice a bounce).
class RegionBoxes {
public:
    RegionBoxes() = default;
    explicit RegionBoxes(std::span<const bvh::Aabb> boxes) {
        for (const bvh::Aabb& box : boxes) add(box);
    }
    void add(const bvh::Aabb& box);
    size_t size() const { return lo_[0].size(); }

    // The smallest t in [ray tmin, tmax] at which the ray enters any of the boxes; +infinity where it
    // enters none. A zero direction component tests the origin against the slab (a point on its face is
    // inside); NaN slab distances widen the interval (never cull a ray that might hit). Each slab distance
    // is widened by 1e-6 of itself, as the kernels' box test, so a grazing far ray is kept.
    float entry(const gpu::Ray& ray, float tmax) const;

private:
    std::vector<float> lo_[3], hi_[3];
};

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
    // One round: each rank sends the rays listed for each destination, traces what it receives and
    // answers; the answers are merged into `rays` in sender order.
    void visitClosest(std::vector<core::WireRay>& rays, const std::vector<std::vector<uint32_t>>& destinations,
                      core::RankTracer& tracer);

    Communicator communicator_;
    // Every rank's boxes as shared by the last shareRegions (this rank's own included), each grown by a
    // margin that covers float rounding in the entry test; indexed by rank.
    std::vector<RegionBoxes> regions_;
    core::ExchangeStats stats_;
};

// RegionBoxes::entry for boxes given as they are.
inline float regionEntry(const gpu::Ray& ray, float tmax, std::span<const bvh::Aabb> boxes) {
    return RegionBoxes(boxes).entry(ray, tmax);
}

}  // namespace ripple::mpi
