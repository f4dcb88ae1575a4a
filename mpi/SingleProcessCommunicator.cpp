// Communicator without MPI (Ripple built with RIPPLE_WITH_MPI off): one process, rank 0 of 1; every
// collective returns its input.
#include "mpi/Communicator.h"

namespace ripple::mpi {

struct Communicator::Handle {};

bool mpiActive() { return false; }

Communicator::Communicator() = default;
Communicator::Communicator(std::shared_ptr<Handle> handle) : handle_(std::move(handle)) {}
Communicator Communicator::world() { return Communicator(); }
Communicator Communicator::fromHandle(const void*) { return Communicator(); }

Communicator::NodeRanks Communicator::nodeRanks() const { return {}; }
uint64_t Communicator::sum(uint64_t value) const { return value; }
uint64_t Communicator::max(uint64_t value) const { return value; }
void Communicator::min(std::span<float>) const {}
void Communicator::max(std::span<float>) const {}
void Communicator::minMax(std::span<const uint64_t> values, std::span<uint64_t> lowest,
                          std::span<uint64_t> highest) const {
    if (lowest.size() != values.size() || highest.size() != values.size())
        throw MpiError("minMax: result spans do not match the values");
    for (size_t i = 0; i < values.size(); ++i) lowest[i] = highest[i] = values[i];
}
std::vector<std::vector<uint8_t>> Communicator::allgather(std::span<const uint8_t> bytes) const {
    return {std::vector<uint8_t>(bytes.begin(), bytes.end())};
}
std::vector<std::vector<uint8_t>> Communicator::gatherToRoot(std::span<const uint8_t> bytes) const {
    return {std::vector<uint8_t>(bytes.begin(), bytes.end())};
}
std::vector<std::vector<uint8_t>> Communicator::alltoallv(const std::vector<std::vector<uint8_t>>& outgoing) const {
    return {outgoing.empty() ? std::vector<uint8_t>() : outgoing.front()};
}
void Communicator::alltoallv(std::span<const uint8_t> send, std::span<const uint64_t> sendCounts,
                             std::vector<uint8_t>& received, std::vector<uint64_t>& receivedOffsets) const {
    const uint64_t count = sendCounts.empty() ? 0 : sendCounts.front();
    if (sendCounts.size() != 1 || count > send.size()) throw MpiError("alltoallv: send counts do not match one rank");
    received.assign(send.begin(), send.begin() + long(count));
    receivedOffsets = {0, count};
}
void Communicator::gatherToRoot(std::span<const uint8_t> bytes, std::vector<uint8_t>& all,
                                std::vector<uint64_t>& offsets) const {
    all.assign(bytes.begin(), bytes.end());
    offsets = {0, bytes.size()};
}
const void* Communicator::selfHandle() { return nullptr; }
std::shared_ptr<const void> Communicator::copyHandle(const void*) { return nullptr; }
std::vector<uint8_t> Communicator::ringShift(std::span<const uint8_t> bytes) const {
    return std::vector<uint8_t>(bytes.begin(), bytes.end());
}
void Communicator::broadcast(std::span<uint8_t>) const {}
void Communicator::barrier() const {}
void Communicator::barrierOrAbort(double, const std::string&) const {}
void Communicator::abort(const std::string& message) const { throw MpiError(message); }
Communicator Communicator::withMessageLimit(uint64_t) const { return *this; }

}  // namespace ripple::mpi

#include "mpi/Runtime.h"

namespace ripple::mpi {

Runtime::Runtime(int*, char***) {}
Runtime::~Runtime() { (void)started_; }

}  // namespace ripple::mpi
