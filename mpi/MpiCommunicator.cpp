// Communicator on MPI (see Communicator.h). The application's communicator is duplicated, so Ripple's
// messages never match the application's; the duplicate is freed with the last Communicator that uses
// it, unless MPI has been finalized by then.
#include "mpi/Communicator.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string_view>

namespace ripple::mpi {

namespace {

constexpr int kRingTag = 7301;

// One check for every MPI call: names the call and MPI's own message for the code.
void check(int code, const char* call) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING] = {};
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw MpiError(std::string(call) + " failed: " + std::string(text, size_t(length)));
}
#define RIPPLE_MPI_CHECK(call) check((call), #call)

int countOf(size_t bytes) {
    if (bytes > size_t(std::numeric_limits<int>::max()))
        throw MpiError("message of " + std::to_string(bytes) + " bytes exceeds MPI's int count");
    return static_cast<int>(bytes);
}

}  // namespace

// Messages and buffer offsets are MPI ints. A rank that found its own too large and threw alone would leave
// the others waiting in the collective forever, so each collective that moves bytes first makes every rank
// know the largest any rank needs (from counts it exchanges anyway, or by one reduction), and all throw
// alike.
void Communicator::checkMessagesFit(uint64_t largest, const char* call) const {
    if (largest <= maxMessageBytes_) return;
    throw MpiError(std::string(call) + ": a rank's messages need " + std::to_string(largest) +
                   " bytes in one buffer, more than the " + std::to_string(maxMessageBytes_) +
                   " one MPI call can move (every rank stops)");
}

Communicator Communicator::withMessageLimit(uint64_t bytes) const {
    Communicator limited = *this;
    limited.maxMessageBytes_ = std::min<uint64_t>(bytes, maxMessageBytes_);
    return limited;
}

struct Communicator::Handle {
    MPI_Comm comm = MPI_COMM_NULL;
    ~Handle() {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
    }
};

bool mpiActive() {
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    return initialized && !finalized;
}

Communicator::Communicator() = default;

Communicator::Communicator(std::shared_ptr<Handle> handle) : handle_(std::move(handle)) {
    RIPPLE_MPI_CHECK(MPI_Comm_set_errhandler(handle_->comm, MPI_ERRORS_RETURN));
    RIPPLE_MPI_CHECK(MPI_Comm_rank(handle_->comm, &rank_));
    RIPPLE_MPI_CHECK(MPI_Comm_size(handle_->comm, &size_));
}

Communicator Communicator::world() { return fromHandle(nullptr); }

Communicator Communicator::fromHandle(const void* handle) {
    if (!mpiActive()) return Communicator();
    const MPI_Comm source = handle ? *static_cast<const MPI_Comm*>(handle) : MPI_COMM_WORLD;
    if (source == MPI_COMM_NULL) throw MpiError("the MPI communicator given is MPI_COMM_NULL");
    auto duplicate = std::make_shared<Handle>();
    RIPPLE_MPI_CHECK(MPI_Comm_dup(source, &duplicate->comm));
    return Communicator(std::move(duplicate));
}

Communicator::NodeRanks Communicator::nodeRanks() const {
    if (!handle_) return {};
    MPI_Comm node = MPI_COMM_NULL;
    RIPPLE_MPI_CHECK(MPI_Comm_split_type(handle_->comm, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node));
    NodeRanks result;
    const int rankResult = MPI_Comm_rank(node, &result.rank);
    const int sizeResult = MPI_Comm_size(node, &result.size);
    MPI_Comm_free(&node);
    check(rankResult, "MPI_Comm_rank of the node communicator");
    check(sizeResult, "MPI_Comm_size of the node communicator");
    return result;
}

uint64_t Communicator::sum(uint64_t value) const {
    if (!distributed()) return value;
    uint64_t result = 0;
    RIPPLE_MPI_CHECK(MPI_Allreduce(&value, &result, 1, MPI_UINT64_T, MPI_SUM, handle_->comm));
    return result;
}

uint64_t Communicator::max(uint64_t value) const {
    if (!distributed()) return value;
    uint64_t result = 0;
    RIPPLE_MPI_CHECK(MPI_Allreduce(&value, &result, 1, MPI_UINT64_T, MPI_MAX, handle_->comm));
    return result;
}

void Communicator::min(std::span<float> values) const {
    if (!distributed() || values.empty()) return;
    RIPPLE_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, values.data(), countOf(values.size()), MPI_FLOAT, MPI_MIN, handle_->comm));
}

void Communicator::max(std::span<float> values) const {
    if (!distributed() || values.empty()) return;
    RIPPLE_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, values.data(), countOf(values.size()), MPI_FLOAT, MPI_MAX, handle_->comm));
}

void Communicator::minMax(std::span<const uint64_t> values, std::span<uint64_t> lowest,
                          std::span<uint64_t> highest) const {
    if (lowest.size() != values.size() || highest.size() != values.size())
        throw MpiError("minMax: " + std::to_string(values.size()) + " values for " + std::to_string(lowest.size()) +
                       " and " + std::to_string(highest.size()) + " results");
    // The maximum of ~v is ~(the minimum of v): both extremes come out of one MPI_MAX.
    const size_t n = values.size();
    std::vector<uint64_t> both(2 * n);
    for (size_t i = 0; i < n; ++i) {
        both[i] = values[i];
        both[n + i] = ~values[i];
    }
    if (distributed() && n > 0)
        RIPPLE_MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, both.data(), countOf(both.size()), MPI_UINT64_T, MPI_MAX,
                                       handle_->comm));
    for (size_t i = 0; i < n; ++i) {
        highest[i] = both[i];
        lowest[i] = ~both[n + i];
    }
}

// Every rank's size on every rank (64-bit), their total checked alike on all; sets `counts` and `offsets`
// as MPI ints.
void Communicator::allgatherSizes(uint64_t mine, std::vector<int>& counts, std::vector<int>& offsets,
                                  const char* call) const {
    std::vector<uint64_t> sizes(static_cast<size_t>(size_));
    RIPPLE_MPI_CHECK(MPI_Allgather(&mine, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, handle_->comm));
    uint64_t total = 0;
    for (const uint64_t size : sizes) total += size;
    checkMessagesFit(total, call);
    counts.assign(sizes.size(), 0);
    offsets.assign(sizes.size(), 0);
    for (size_t r = 0, at = 0; r < sizes.size(); at += sizes[r], ++r) {
        counts[r] = int(sizes[r]);
        offsets[r] = int(at);
    }
}

// MPI_Alltoall of 64-bit counts, then one reduction so that every rank knows whether any rank's send or
// receive buffer is too large: sets the MPI int counts and offsets, returns this rank's receive total.
uint64_t Communicator::exchangeCounts(std::span<const uint64_t> sendSizes, std::vector<int>& sendCounts,
                                      std::vector<int>& sendOffsets, std::vector<int>& receiveCounts,
                                      std::vector<int>& receiveOffsets, const char* call) const {
    const size_t ranks = size_t(size_);
    std::vector<uint64_t> receiveSizes(ranks);
    RIPPLE_MPI_CHECK(
        MPI_Alltoall(sendSizes.data(), 1, MPI_UINT64_T, receiveSizes.data(), 1, MPI_UINT64_T, handle_->comm));
    uint64_t sent = 0, received = 0;
    for (size_t r = 0; r < ranks; ++r) {
        sent += sendSizes[r];
        received += receiveSizes[r];
    }
    checkMessagesFit(max(std::max(sent, received)), call);
    for (size_t r = 0, sendAt = 0, receiveAt = 0; r < ranks;
         sendAt += sendSizes[r], receiveAt += receiveSizes[r], ++r) {
        sendCounts[r] = int(sendSizes[r]);
        sendOffsets[r] = int(sendAt);
        receiveCounts[r] = int(receiveSizes[r]);
        receiveOffsets[r] = int(receiveAt);
    }
    return received;
}

std::vector<std::vector<uint8_t>> Communicator::allgather(std::span<const uint8_t> bytes) const {
    if (!distributed()) return {std::vector<uint8_t>(bytes.begin(), bytes.end())};
    std::vector<int> counts, offsets;
    allgatherSizes(bytes.size(), counts, offsets, "allgather");
    const int mine = counts[size_t(rank_)];
    const size_t total = size_t(offsets.back()) + size_t(counts.back());
    std::vector<uint8_t> all(std::max<size_t>(total, 1));
    RIPPLE_MPI_CHECK(MPI_Allgatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                                    handle_->comm));
    std::vector<std::vector<uint8_t>> result(static_cast<size_t>(size_));
    for (int r = 0; r < size_; ++r)
        result[size_t(r)].assign(all.begin() + offsets[size_t(r)], all.begin() + offsets[size_t(r)] + counts[size_t(r)]);
    return result;
}

std::vector<std::vector<uint8_t>> Communicator::gatherToRoot(std::span<const uint8_t> bytes) const {
    if (!distributed()) return {std::vector<uint8_t>(bytes.begin(), bytes.end())};
    std::vector<int> counts, offsets;
    allgatherSizes(bytes.size(), counts, offsets, "gatherToRoot");
    const int mine = counts[size_t(rank_)];
    const size_t total = rank_ == 0 ? size_t(offsets.back()) + size_t(counts.back()) : 0;
    std::vector<uint8_t> all(std::max<size_t>(total, 1));
    RIPPLE_MPI_CHECK(MPI_Gatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, 0,
                                 handle_->comm));
    std::vector<std::vector<uint8_t>> result;
    if (rank_ != 0) return result;
    result.resize(static_cast<size_t>(size_));
    for (int r = 0; r < size_; ++r)
        result[size_t(r)].assign(all.begin() + offsets[size_t(r)], all.begin() + offsets[size_t(r)] + counts[size_t(r)]);
    return result;
}

std::shared_ptr<const void> Communicator::copyHandle(const void* handle) {
    if (!handle) return nullptr;
    return std::make_shared<MPI_Comm>(*static_cast<const MPI_Comm*>(handle));
}

const void* Communicator::selfHandle() {
    static const MPI_Comm self = MPI_COMM_SELF;
    return &self;
}

std::vector<std::vector<uint8_t>> Communicator::alltoallv(const std::vector<std::vector<uint8_t>>& outgoing) const {
    if (outgoing.size() != size_t(size_))
        throw MpiError("alltoallv: " + std::to_string(outgoing.size()) + " outgoing buffers for " +
                       std::to_string(size_) + " ranks");
    if (!distributed()) return {outgoing.front()};
    const size_t ranks = size_t(size_);
    std::vector<uint64_t> sizes(ranks);
    std::vector<int> sendCounts(ranks), sendOffsets(ranks), receiveCounts(ranks), receiveOffsets(ranks);
    for (size_t r = 0; r < ranks; ++r) sizes[r] = outgoing[r].size();
    const uint64_t total = exchangeCounts(sizes, sendCounts, sendOffsets, receiveCounts, receiveOffsets, "alltoallv");
    std::vector<uint8_t> sendBuffer;
    for (size_t r = 0; r < ranks; ++r) sendBuffer.insert(sendBuffer.end(), outgoing[r].begin(), outgoing[r].end());
    sendBuffer.resize(std::max<size_t>(sendBuffer.size(), 1));
    std::vector<uint8_t> all(std::max<size_t>(total, 1));
    RIPPLE_MPI_CHECK(MPI_Alltoallv(sendBuffer.data(), sendCounts.data(), sendOffsets.data(), MPI_BYTE, all.data(),
                                   receiveCounts.data(), receiveOffsets.data(), MPI_BYTE, handle_->comm));
    std::vector<std::vector<uint8_t>> result(ranks);
    for (size_t r = 0; r < ranks; ++r)
        result[r].assign(all.begin() + receiveOffsets[r], all.begin() + receiveOffsets[r] + receiveCounts[r]);
    return result;
}

void Communicator::alltoallv(std::span<const uint8_t> send, std::span<const uint64_t> sendCounts,
                             std::vector<uint8_t>& received, std::vector<uint64_t>& receivedOffsets) const {
    const size_t ranks = size_t(size_);
    if (sendCounts.size() != ranks)
        throw MpiError("alltoallv: " + std::to_string(sendCounts.size()) + " send counts for " + std::to_string(ranks) +
                       " ranks");
    uint64_t at = 0;
    for (const uint64_t count : sendCounts) at += count;
    if (at > send.size()) throw MpiError("alltoallv: send counts exceed the send buffer");  // the caller's bug
    if (!distributed()) {
        received.assign(send.begin(), send.begin() + long(at));
        receivedOffsets = {0, at};
        return;
    }
    std::vector<int> counts(ranks), offsets(ranks), receiveCounts(ranks), receiveOffsets(ranks);
    exchangeCounts(sendCounts, counts, offsets, receiveCounts, receiveOffsets, "alltoallv");
    receivedOffsets.assign(ranks + 1, 0);
    for (size_t r = 0; r < ranks; ++r) receivedOffsets[r + 1] = receivedOffsets[r] + uint64_t(receiveCounts[r]);
    received.resize(std::max<size_t>(receivedOffsets[ranks], 1));
    static const uint8_t none = 0;
    RIPPLE_MPI_CHECK(MPI_Alltoallv(send.empty() ? &none : send.data(), counts.data(), offsets.data(), MPI_BYTE,
                                   received.data(), receiveCounts.data(), receiveOffsets.data(), MPI_BYTE, handle_->comm));
    received.resize(receivedOffsets[ranks]);
}

void Communicator::gatherToRoot(std::span<const uint8_t> bytes, std::vector<uint8_t>& all,
                                std::vector<uint64_t>& offsets) const {
    if (!distributed()) {
        all.assign(bytes.begin(), bytes.end());
        offsets = {0, bytes.size()};
        return;
    }
    std::vector<int> counts, displacements;
    allgatherSizes(bytes.size(), counts, displacements, "gatherToRoot");
    const int mine = counts[size_t(rank_)];
    offsets.assign(rank_ == 0 ? size_t(size_) + 1 : 0, 0);
    for (int r = 0; r < size_ && rank_ == 0; ++r) offsets[size_t(r) + 1] = offsets[size_t(r)] + uint64_t(counts[size_t(r)]);
    all.resize(rank_ == 0 ? std::max<size_t>(offsets.back(), 1) : 1);
    static const uint8_t none = 0;
    RIPPLE_MPI_CHECK(MPI_Gatherv(bytes.empty() ? &none : bytes.data(), mine, MPI_BYTE, all.data(), counts.data(),
                                 displacements.data(), MPI_BYTE, 0, handle_->comm));
    all.resize(rank_ == 0 ? offsets.back() : 0);
}

std::vector<uint8_t> Communicator::ringShift(std::span<const uint8_t> bytes) const {
    if (!distributed()) return std::vector<uint8_t>(bytes.begin(), bytes.end());
    const int next = (rank_ + 1) % size_, previous = (rank_ + size_ - 1) % size_;
    uint64_t outgoing = bytes.size(), incoming = 0;
    RIPPLE_MPI_CHECK(MPI_Sendrecv(&outgoing, 1, MPI_UINT64_T, next, kRingTag, &incoming, 1, MPI_UINT64_T, previous,
                                  kRingTag, handle_->comm, MPI_STATUS_IGNORE));
    checkMessagesFit(max(std::max(outgoing, incoming)), "ringShift");
    std::vector<uint8_t> received(incoming);
    RIPPLE_MPI_CHECK(MPI_Sendrecv(bytes.data(), countOf(bytes.size()), MPI_BYTE, next, kRingTag + 1, received.data(),
                                  countOf(received.size()), MPI_BYTE, previous, kRingTag + 1, handle_->comm,
                                  MPI_STATUS_IGNORE));
    return received;
}

void Communicator::broadcast(std::span<uint8_t> bytes) const {
    if (!distributed() || bytes.empty()) return;
    RIPPLE_MPI_CHECK(MPI_Bcast(bytes.data(), countOf(bytes.size()), MPI_BYTE, 0, handle_->comm));
}

void Communicator::barrier() const {
    if (distributed() && mpiActive()) RIPPLE_MPI_CHECK(MPI_Barrier(handle_->comm));
}

void Communicator::barrierOrAbort(double seconds, const std::string& message) const {
    if (!distributed() || !mpiActive()) return;
    MPI_Request request = MPI_REQUEST_NULL;
    RIPPLE_MPI_CHECK(MPI_Ibarrier(handle_->comm, &request));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (int done = 0;;) {
        RIPPLE_MPI_CHECK(MPI_Test(&request, &done, MPI_STATUS_IGNORE));
        if (done) return;
        if (std::chrono::steady_clock::now() > deadline)
            abort(message + " (a rank did not reach it within " + std::to_string(seconds) + " s)");
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

void Communicator::abort(const std::string& message) const {
    if (!distributed()) throw MpiError(message);
    std::cerr << "ripple: rank " << rank_ << " of " << size_ << ": " << message << " (aborting all ranks)" << std::endl;
    MPI_Abort(handle_->comm, 1);
    std::abort();  // MPI_Abort should not return; never go on rendering if it did
}

}  // namespace ripple::mpi

#include "mpi/Runtime.h"

namespace ripple::mpi {

namespace {

// Whether an MPI launcher started this process (see Runtime.h).
bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "MV2_COMM_WORLD_SIZE"})
        if (std::getenv(name)) return true;
    const char* force = std::getenv("RIPPLE_MPI_INIT");
    return force && std::string_view(force) == "1";
}

}  // namespace

// Serialized: Ripple calls MPI from one thread at a time (a data-parallel frame renders on the thread that
// called anariRenderFrame), which is all the application is promised too.
Runtime::Runtime(int* argc, char*** argv) {
    if (mpiActive() || !launchedByMpi()) return;
    int provided = 0;
    RIPPLE_MPI_CHECK(MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided));
    started_ = true;
}

Runtime::~Runtime() {
    if (started_ && mpiActive()) MPI_Finalize();
}

}  // namespace ripple::mpi
