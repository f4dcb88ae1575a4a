// ripple-render --list-devices (see ListDevices.h).
#include "apps/ripple-render/ListDevices.h"

#include <cstdio>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

int listDevices(const Options& options, const mpi::Communicator& ranks, Session& s) {
    static StatusLog log{"ripple-render", options.quiet, 0};  // the device may report until it is released
    openAnariDevice(options.library, log, s);
    const char* text = nullptr;
    if (!anariGetProperty(s.device, s.device, "ripple.vulkanDevices", ANARI_STRING, &text, sizeof(text), ANARI_WAIT) ||
        !text)
        throw std::runtime_error("the ANARI library '" + options.library +
                                 "' does not list its Vulkan devices (it has no device property ripple.vulkanDevices)");
    const std::string mine = text;
    const std::vector<std::vector<uint8_t>> all =
        ranks.gatherToRoot(std::span(reinterpret_cast<const uint8_t*>(mine.data()), mine.size()));
    for (size_t r = 0; r < all.size(); ++r) {
        if (ranks.distributed()) std::printf("rank %zu of %d:\n", r, ranks.size());
        std::fwrite(all[r].data(), 1, all[r].size(), stdout);
    }
    std::fflush(stdout);
    return 0;
}

}  // namespace ripple::apps
