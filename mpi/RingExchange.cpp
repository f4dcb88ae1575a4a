// Queue cycling (see RingExchange.h). Batches travel whole and in order, so a ray's slot in the batch
// that comes home is its slot in the home queue; the id each ray carries checks that.
#include "mpi/RingExchange.h"

#include <chrono>
#include <cstring>
#include <string>

namespace ripple::mpi {

RingExchange::RingExchange(Communicator communicator) : communicator_(std::move(communicator)) {}

template <class WireItem, class Visit>
void RingExchange::cycle(std::vector<WireItem>& items, Visit visit) {
    const int ranks = communicator_.size();
    if (ranks <= 1) return;
    const size_t homeCount = items.size();
    std::vector<WireItem> batch = std::move(items);
    for (int hop = 1; hop <= ranks; ++hop) {
        const auto bytes = std::span(reinterpret_cast<const uint8_t*>(batch.data()), batch.size() * sizeof(WireItem));
        stats_.raysSent += batch.size();
        stats_.bytesSent += bytes.size();
        ++stats_.hops;
        std::vector<uint8_t> received = communicator_.ringShift(bytes);
        if (received.size() % sizeof(WireItem) != 0)
            throw MpiError("ray exchange: received " + std::to_string(received.size()) + " bytes, not whole rays");
        batch.resize(received.size() / sizeof(WireItem));
        if (!received.empty()) std::memcpy(batch.data(), received.data(), received.size());
        if (hop < ranks) {  // the last hop is the one home
            stats_.raysReceived += batch.size();
            const auto start = std::chrono::steady_clock::now();
            visit(std::span<WireItem>(batch));
            stats_.visitMicroseconds += uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(
                                                     std::chrono::steady_clock::now() - start).count());
        }
    }
    if (batch.size() != homeCount)
        throw MpiError("ray exchange: " + std::to_string(homeCount) + " rays left rank " + std::to_string(rank()) +
                       " and " + std::to_string(batch.size()) + " came back");
    for (size_t i = 0; i < batch.size(); ++i)
        if (batch[i].homeRank != rank() || batch[i].id != i)
            throw MpiError("ray exchange: a ray came home to the wrong rank or slot");
    items = std::move(batch);
}

void RingExchange::exchangeClosest(std::vector<core::WireRay>& rays, core::RankTracer& tracer) {
    cycle(rays, [&](std::span<core::WireRay> visitors) { tracer.traceClosest(visitors); });
}

// A shadow ray occluded at home is settled: only the others travel, renumbered to their slot in the
// travelling batch (which keeps its order, so each comes back to its slot).
void RingExchange::exchangeShadow(std::vector<core::WireShadowRay>& rays, core::RankTracer& tracer) {
    std::vector<uint32_t> open;
    std::vector<core::WireShadowRay> travelling;
    for (size_t i = 0; i < rays.size(); ++i) {
        if ((rays[i].occlusion & 0xFFu) == gpu::HIT_FOUND) continue;
        open.push_back(uint32_t(i));
        travelling.push_back(rays[i]);
        travelling.back().id = uint32_t(travelling.size() - 1);
    }
    cycle(travelling, [&](std::span<core::WireShadowRay> visitors) { tracer.traceShadow(visitors); });
    for (size_t k = 0; k < open.size(); ++k) {
        rays[open[k]].occlusion = travelling[k].occlusion;
        rays[open[k]].transmittance = travelling[k].transmittance;
    }
}

}  // namespace ripple::mpi
