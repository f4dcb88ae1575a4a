// The Vulkan context every GPU test shares: validation layers on, so any validation message fails the test
// that caused it (see ValidationGuard). RIPPLE_VK_VALIDATION=0 turns them off: the sanitizer build's tests
// set it (tests/CMakeLists.txt). The device reads the same variable, off unless it is 1.
#pragma once

#include "core/vk/Context.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <string_view>

namespace ripple::test {

// The options of testContext(); tests that need a context of their own (another memory mode, lowered
// limits) start from them.
inline vk::ContextOptions testContextOptions() {
    const char* validation = std::getenv("RIPPLE_VK_VALIDATION");
    return vk::ContextOptions{.validation = !validation || std::string_view(validation) != "0"};
}

inline vk::Context& testContext() {
    static vk::Context context(testContextOptions());
    return context;
}

// Declare one at the top of a GPU test: on scope exit it fails the test if validation spoke meanwhile.
class ValidationGuard {
public:
    ValidationGuard() : before_(testContext().validationMessageCount()) {}
    ~ValidationGuard() {
        const uint64_t now = testContext().validationMessageCount();
        CHECK_MESSAGE(now == before_, "Vulkan validation: " << testContext().lastValidationMessage());
    }

private:
    uint64_t before_;
};

}  // namespace ripple::test
