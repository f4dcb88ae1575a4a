// The ranks a data-parallel render runs on, behind plain C++ (this header does not include mpi.h): an MPI
// communicator when Ripple is built with MPI and MPI is initialized, else a single process whose
// collectives return at once. Failed MPI calls throw MpiError naming the call and MPI's message.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::mpi {

class MpiError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Built with MPI, and MPI_Init has run (and MPI_Finalize has not).
bool mpiActive();

class Communicator {
public:
    // One process, rank 0 of 1: no MPI call is ever made.
    Communicator();
    // MPI_COMM_WORLD where MPI is active, else a single process.
    static Communicator world();
    // The application's communicator: `handle` points to an MPI_Comm. Null, or MPI not active: world().
    static Communicator fromHandle(const void* handle);
    // The address of an MPI_Comm holding MPI_COMM_SELF (nullptr without MPI): given to a device that
    // must render alone while its caller composites across ranks.
    static const void* selfHandle();
    // A copy of the MPI_Comm that `handle` points to (nullptr for nullptr, or without MPI): parameters name
    // the application's MPI_Comm by address, and the application's variable may be gone by the time the
    // communicator is first used.
    static std::shared_ptr<const void> copyHandle(const void* handle);

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool distributed() const { return size_ > 1; }

    // This rank among the ranks of the communicator that share its node (MPI_Comm_split_type with
    // MPI_COMM_TYPE_SHARED, ordered by rank): what picks its GPU (vk::ContextOptions::localRank).
    // Collective. One process: rank 0 of 1.
    struct NodeRanks {
        int rank = 0;
        int size = 1;
    };
    NodeRanks nodeRanks() const;

    uint64_t sum(uint64_t value) const;
    uint64_t max(uint64_t value) const;
    // Element-wise minimum / maximum over ranks, in place.
    void min(std::span<float> values) const;
    void max(std::span<float> values) const;
    // Element-wise minimum and maximum over ranks of `values`, in one reduction (a check that the ranks
    // agree costs one collective whatever the number of fields).
    void minMax(std::span<const uint64_t> values, std::span<uint64_t> lowest, std::span<uint64_t> highest) const;
    // Every rank's bytes, indexed by rank (on every rank).
    std::vector<std::vector<uint8_t>> allgather(std::span<const uint8_t> bytes) const;
    // Every rank's bytes on rank 0 (indexed by rank); empty on the others.
    std::vector<std::vector<uint8_t>> gatherToRoot(std::span<const uint8_t> bytes) const;
    // outgoing[r] goes to rank r; returns what each rank sent here, indexed by sender (MPI_Alltoallv).
    std::vector<std::vector<uint8_t>> alltoallv(const std::vector<std::vector<uint8_t>>& outgoing) const;
    // The same without copies for large messages: `send` holds the bytes for rank 0, then rank 1, ...
    // (sendCounts[r] of them); `received` gets what each rank sent here, sender s's bytes at
    // [receivedOffsets[s], receivedOffsets[s + 1]). The buffers are the caller's, kept between calls.
    void alltoallv(std::span<const uint8_t> send, std::span<const uint64_t> sendCounts, std::vector<uint8_t>& received,
                   std::vector<uint64_t>& receivedOffsets) const;
    // Every rank's bytes in one buffer on rank 0 (rank r's at [offsets[r], offsets[r + 1])); others get
    // nothing.
    void gatherToRoot(std::span<const uint8_t> bytes, std::vector<uint8_t>& all, std::vector<uint64_t>& offsets) const;
    // Rank 0's `bytes` into every rank's `bytes` (the same size on every rank).
    void broadcast(std::span<uint8_t> bytes) const;
    // Sends to rank + 1 and receives from rank - 1 (cyclically): one hop of a ring.
    std::vector<uint8_t> ringShift(std::span<const uint8_t> bytes) const;
    void barrier() const;
    // A barrier for places that must not hang (destructors, the device's last release): when a peer has not
    // entered it within `seconds`, every rank is ended with `message` (MPI offers no way to leave a
    // collective a peer never enters). Returns at once with one rank.
    void barrierOrAbort(double seconds, const std::string& message) const;
    // Ends every rank of the communicator (MPI_Abort) after printing `message` to stderr; returns only
    // with one rank, where it throws MpiError instead.
    void abort(const std::string& message) const;

    // A copy whose collectives refuse buffers over `bytes` (at most MPI's int count, 2^31 - 1, the default),
    // on every rank alike: a rank whose messages do not fit throws MpiError on every rank instead of
    // leaving the others waiting. Tests lower it to check that agreement without gigabyte buffers.
    Communicator withMessageLimit(uint64_t bytes) const;

private:
    struct Handle;
    explicit Communicator(std::shared_ptr<Handle> handle);
    void checkMessagesFit(uint64_t largest, const char* call) const;
    void allgatherSizes(uint64_t mine, std::vector<int>& counts, std::vector<int>& offsets, const char* call) const;
    uint64_t exchangeCounts(std::span<const uint64_t> sendSizes, std::vector<int>& sendCounts,
                            std::vector<int>& sendOffsets, std::vector<int>& receiveCounts,
                            std::vector<int>& receiveOffsets, const char* call) const;

    std::shared_ptr<Handle> handle_;
    int rank_ = 0;
    int size_ = 1;
    uint64_t maxMessageBytes_ = 2147483647;  // MPI's int count
};

}  // namespace ripple::mpi
