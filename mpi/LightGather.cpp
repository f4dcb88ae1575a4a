// Lights travel as their bytes: core::Light and gpu::LightRecord are plain data, laid out alike on every
// rank of one build.
#include "mpi/LightGather.h"

#include <cstring>
#include <type_traits>

namespace ripple::mpi {

static_assert(std::is_trivially_copyable_v<core::Light>);
static_assert(std::is_trivially_copyable_v<gpu::LightRecord>);

std::vector<core::Light> gatherLights(const Communicator& communicator, const std::vector<core::Light>& local) {
    if (!communicator.distributed()) return local;
    const auto bytes = std::span(reinterpret_cast<const uint8_t*>(local.data()), local.size() * sizeof(core::Light));
    std::vector<core::Light> all;
    for (const std::vector<uint8_t>& part : communicator.allgather(bytes)) {
        const size_t first = all.size();
        all.resize(first + part.size() / sizeof(core::Light));
        if (!part.empty()) std::memcpy(static_cast<void*>(all.data() + first), part.data(), part.size());
    }
    return all;
}

std::vector<gpu::LightRecord> gatherForeignLightRecords(const Communicator& communicator,
                                                        const std::vector<gpu::LightRecord>& local) {
    if (!communicator.distributed()) return {};
    const auto bytes = std::span(reinterpret_cast<const uint8_t*>(local.data()), local.size() * sizeof(gpu::LightRecord));
    const std::vector<std::vector<uint8_t>> parts = communicator.allgather(bytes);
    std::vector<gpu::LightRecord> foreign;
    for (size_t r = 0; r < parts.size(); ++r) {
        if (int(r) == communicator.rank()) continue;
        if (parts[r].size() % sizeof(gpu::LightRecord) != 0)
            throw MpiError("rank " + std::to_string(r) + " sent light records of a different layout");
        const size_t first = foreign.size();
        foreign.resize(first + parts[r].size() / sizeof(gpu::LightRecord));
        if (!parts[r].empty()) std::memcpy(static_cast<void*>(foreign.data() + first), parts[r].data(), parts[r].size());
    }
    return foreign;
}

}  // namespace ripple::mpi
