// The Vulkan context every GPU test shares: validation layers on, so any validation message fails the test
// that caused it (see ValidationGuard).
#pragma once

#include "core/vk/Context.h"

#include <doctest/doctest.h>

namespace ripple::test {

inline vk::Context& testContext() {
    static vk::Context context(vk::ContextOptions{.validation = true});
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
