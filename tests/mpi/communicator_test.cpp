// mpi::Communicator's collectives when one rank's messages are too large for one MPI call: every rank must
// throw, none may wait in the collective for a peer that gave up. The limit is lowered to 1,000 bytes so
// that no gigabyte buffer is needed; without the agreement, the ranks that fit hang and the test times out.
// Run under mpirun with 1-4 ranks.
#include "mpi/Communicator.h"

#include <doctest/doctest.h>

#include <vector>

using namespace ripple;

TEST_CASE("communicator: a message too large on one rank stops every rank alike, and the ranks go on together") {
    const mpi::Communicator world = mpi::Communicator::world();
    if (!world.distributed()) return;  // one rank makes no MPI call
    const mpi::Communicator limited = world.withMessageLimit(1000);
    const auto rank = size_t(world.rank()), n = size_t(world.size());
    const std::vector<uint8_t> large(1001, 7), small(1, 7);
    const std::span<const uint8_t> lastSendsLarge = rank == n - 1 ? std::span(large) : std::span(small);

    std::vector<uint8_t> received;
    std::vector<uint64_t> offsets;
    // Sender side: the last rank's contribution alone is over the limit.
    CHECK_THROWS_AS(limited.gatherToRoot(lastSendsLarge, received, offsets), mpi::MpiError);
    CHECK_THROWS_AS((void)limited.gatherToRoot(lastSendsLarge), mpi::MpiError);
    CHECK_THROWS_AS((void)limited.allgather(lastSendsLarge), mpi::MpiError);
    CHECK_THROWS_AS((void)limited.ringShift(lastSendsLarge), mpi::MpiError);
    // Receiver side: every rank sends rank 0 600 bytes (each send fits), which rank 0 alone cannot take.
    std::vector<uint64_t> counts(n, 1);
    counts[0] = 600;
    const std::vector<uint8_t> send(600 + n, 7);
    CHECK_THROWS_AS(limited.alltoallv(send, counts, received, offsets), mpi::MpiError);
    std::vector<std::vector<uint8_t>> outgoing(n, small);
    outgoing[0] = std::vector<uint8_t>(600, 7);
    CHECK_THROWS_AS((void)limited.alltoallv(outgoing), mpi::MpiError);

    // Every rank left each collective at the same point: the next ones match up.
    CHECK(world.sum(1) == n);
    counts.assign(n, 1);
    limited.alltoallv(send, counts, received, offsets);
    CHECK(received.size() == n);
    CHECK(limited.gatherToRoot(small).size() == (rank == 0 ? n : 0));
}
