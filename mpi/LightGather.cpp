// Lights travel as their bytes: core::Light is plain data, laid out alike on every rank of one build.
#include "mpi/LightGather.h"

#include <cstring>
#include <type_traits>

namespace ripple::mpi {

static_assert(std::is_trivially_copyable_v<core::Light>);

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

}  // namespace ripple::mpi
