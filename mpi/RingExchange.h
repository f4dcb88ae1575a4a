// The ring ray exchange: after its local trace each rank passes its queue to rank + 1 and receives the
// queue of rank - 1, traces the visitors against its own part of the scene, and passes them on; after
// N - 1 hops every queue has met every rank, and one more hop takes it home. Memory per rank stays one
// queue in and one out, whatever the rank count.
#pragma once

#include "core/render/RayExchange.h"
#include "mpi/Communicator.h"

namespace ripple::mpi {

class RingExchange final : public core::RayExchange {
public:
    explicit RingExchange(Communicator communicator);

    uint32_t rank() const override { return uint32_t(communicator_.rank()); }
    uint32_t rankCount() const override { return uint32_t(communicator_.size()); }
    void exchangeClosest(std::vector<core::WireRay>& rays, core::RankTracer& tracer) override;
    void exchangeShadow(std::vector<core::WireShadowRay>& rays, core::RankTracer& tracer) override;
    uint64_t sum(uint64_t local) override { return communicator_.sum(local); }
    uint64_t max(uint64_t local) override { return communicator_.max(local); }
    core::ExchangeStats stats() const override { return stats_; }
    void resetStats() override { stats_ = {}; }

    const Communicator& communicator() const { return communicator_; }

private:
    template <class WireItem, class Visit>
    void cycle(std::vector<WireItem>& items, Visit visit);

    Communicator communicator_;
    core::ExchangeStats stats_;
};

}  // namespace ripple::mpi
