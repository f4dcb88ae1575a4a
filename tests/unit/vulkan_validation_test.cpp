// The validation layer's checks that lavapipe cannot show by misbehaving, proven able to see what they are
// for: synchronization validation reports two writes with no barrier between them (and vk::computeBarrier
// silences it), and GPU-assisted validation reports a kernel's write past its buffer through a device
// address. Each runs only where its feature is enabled (VK_LAYER_ENABLES, as tests/CMakeLists.txt sets it).
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "shaders/test_indexed_write.spv.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <string>

using namespace ripple;

namespace {

// Off where the suite runs without the layer (RIPPLE_VK_VALIDATION=0: the sanitizer build).
bool layerFeatureEnabled(const char* feature) {
    const char* validation = std::getenv("RIPPLE_VK_VALIDATION");
    const char* enables = std::getenv("VK_LAYER_ENABLES");
    return !(validation && std::string(validation) == "0") && enables && std::string(enables).find(feature) != std::string::npos;
}

// A context of its own: the hazards made here must not count against the shared test context.
vk::Context validatedContext() { return vk::Context({.validation = true, .printDeviceChoice = false, .rayQuery = false}); }

}  // namespace

TEST_CASE("synchronization validation reports a missing barrier, and vk::computeBarrier silences it") {
    if (!layerFeatureEnabled("VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT")) {
        MESSAGE("skipped: synchronization validation is not enabled (VK_LAYER_ENABLES)");
        return;
    }
    const vk::Context context = validatedContext();
    const vk::Buffer buffer(context, 1024, "sync validation target");
    const uint64_t before = context.validationMessageCount();
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 1);
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 2);  // no barrier: write after write
    });
    CHECK(context.validationMessageCount() > before);
    CHECK_MESSAGE(context.lastValidationMessage().find("SYNC-HAZARD-WRITE-AFTER-WRITE") != std::string::npos,
                  context.lastValidationMessage());
    const uint64_t reported = context.validationMessageCount();
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 1);
        vk::computeBarrier(cmd);
        vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 2);
    });
    CHECK_MESSAGE(context.validationMessageCount() == reported, context.lastValidationMessage());
}

TEST_CASE("GPU-assisted validation reports a kernel's write past its buffer through a device address") {
    if (!layerFeatureEnabled("VK_VALIDATION_FEATURE_ENABLE_GPU_ASSISTED_EXT")) {
        MESSAGE("skipped: GPU-assisted validation is not enabled (VK_LAYER_ENABLES)");
        return;
    }
    const vk::Context context = validatedContext();
    const vk::Buffer buffer(context, 256, "GPU-assisted validation target");
    struct Params {
        uint64_t address;
        uint32_t index, value;
    };
    const vk::ComputePipeline write(context, shaders::test_indexed_write, "test_indexed_write", sizeof(Params));
    const auto run = [&](uint32_t index) {
        const Params p{buffer.address(), index, 7};
        context.submitAndWait([&](VkCommandBuffer cmd) {
            write.bind(cmd);
            write.pushConstants(cmd, &p, sizeof p);
            vkCmdDispatch(cmd, 1, 1, 1);
        });
    };
    const uint64_t before = context.validationMessageCount();
    run(63);  // the last word: in bounds
    CHECK_MESSAGE(context.validationMessageCount() == before, context.lastValidationMessage());
    uint32_t last = 0;
    buffer.download(&last, sizeof last, 63 * 4);
    CHECK(last == 7);
    run(64 + 1024);  // 4 KiB past the end: the layer stops the write and reports it
    CHECK(context.validationMessageCount() > before);
    MESSAGE("reported: " << context.lastValidationMessage());
}
