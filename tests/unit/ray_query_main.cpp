// doctest entry point of the ray-query suite: where the Vulkan device has no ray queries the program runs
// nothing and returns 77, which CMake declares as the test's SKIP_RETURN_CODE (as unit/main.cpp does for
// absent data), so CTest reports the suite as skipped, never as passed.
#define DOCTEST_CONFIG_IMPLEMENT
#include "core/vk/Context.h"

#include <doctest/doctest.h>

#include <cstdio>

int main(int argc, char** argv) {
    {
        const ripple::vk::Context probe(ripple::vk::ContextOptions{.printDeviceChoice = false});
        if (!probe.supportsRayQuery()) {
            std::printf("skipped: Vulkan device %s has no ray queries (lacks %s)\n", probe.deviceName().c_str(),
                        probe.rayQueryMissing().c_str());
            return 77;
        }
    }
    doctest::Context context(argc, argv);
    return context.run();
}
