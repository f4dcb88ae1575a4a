// The limits override (vk::ContextOptions::limits, RIPPLE_VK_LIMITS): its parsing, the limits a context
// reports under it, push constants checked against maxPushConstantsSize when a kernel is built, dispatches
// refused beyond maxComputeWorkGroupCount, and a render split to fit 8 workgroups per dispatch that equals
// the unsplit one bit for bit.
#include "core/render/PathTracer.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/LimitsOverride.h"
#include "shaders/pt_accumulate.spv.h"
#include "shaders/shared/path.h"
#include "tests/support/MixedFrame.h"

#include <doctest/doctest.h>

#include <cstring>
#include <string>

using namespace ripple;

namespace {

vk::ContextOptions loweredOptions(const std::string& limits) {
    vk::ContextOptions options = test::testContextOptions();
    options.printDeviceChoice = false;
    options.limits = limits;
    return options;
}

// 8 workgroups of 64: 512 items per dispatch, paths in flight and trace resume pools (lavapipe: 65,535).
vk::Context& eightGroupsContext() {
    static vk::Context context(loweredOptions("maxComputeWorkGroupCount=8"));
    return context;
}

std::string parseError(const char* text) {
    try {
        vk::parseLimitsOverride(text);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "(accepted)";
}

}  // namespace

TEST_CASE("limits override: parsing, and only ever lowering") {
    const vk::LimitsOverride both = vk::parseLimitsOverride(" maxComputeWorkGroupCount=64 , maxPushConstantsSize = 128,");
    CHECK(both.maxComputeWorkGroupCount == 64u);
    CHECK(both.maxPushConstantsSize == 128u);
    CHECK(vk::parseLimitsOverride("").empty());
    CHECK(parseError("maxStorageBufferRange=1024").find("unknown limit; known: maxComputeWorkGroupCount, "
                                                        "maxPushConstantsSize") != std::string::npos);
    CHECK(parseError("maxComputeWorkGroupCount=0").find("'maxComputeWorkGroupCount=0'") != std::string::npos);
    CHECK(parseError("maxComputeWorkGroupCount=4294967296").find("positive integer") != std::string::npos);
    CHECK(parseError("maxComputeWorkGroupCount=12x").find("positive integer") != std::string::npos);
    CHECK(parseError("maxComputeWorkGroupCount").find("not key=value") != std::string::npos);
    CHECK(parseError("maxPushConstantsSize=64,maxPushConstantsSize=32").find("given twice") != std::string::npos);

    VkPhysicalDeviceLimits limits{};
    limits.maxComputeWorkGroupCount[0] = 65535;
    limits.maxComputeWorkGroupCount[1] = limits.maxComputeWorkGroupCount[2] = 1024;
    limits.maxPushConstantsSize = 128;
    const std::string changes = vk::applyLimitsOverride(limits, vk::parseLimitsOverride("maxComputeWorkGroupCount=2000,maxPushConstantsSize=256"));
    CHECK(limits.maxComputeWorkGroupCount[0] == 2000);
    CHECK(limits.maxComputeWorkGroupCount[1] == 1024);  // already lower: kept
    CHECK(limits.maxPushConstantsSize == 128);           // an override never raises a limit
    CHECK(changes == "maxComputeWorkGroupCount 2000 (device 65535)");
}

// A context reports the lowered limits; a kernel whose push constants exceed them is refused when built,
// naming the kernel and the limit, and so is a render that needs it; a dispatch of more workgroups than
// the limit is refused when recorded.
TEST_CASE("limits override: push constants and dispatch sizes are checked against the lowered limits") {
    const VkPhysicalDeviceLimits& device = test::testContext().properties().limits;
    vk::Context narrow(loweredOptions("maxPushConstantsSize=64,maxComputeWorkGroupCount=8"));
    CHECK(narrow.properties().limits.maxPushConstantsSize == std::min(64u, device.maxPushConstantsSize));
    for (int axis = 0; axis < 3; ++axis)
        CHECK(narrow.properties().limits.maxComputeWorkGroupCount[axis] ==
              std::min(8u, device.maxComputeWorkGroupCount[axis]));
    const auto bytes = static_cast<uint32_t>(sizeof(gpu::StageParams));
    REQUIRE(bytes > 64);
    CHECK_THROWS_WITH(vk::ComputePipeline(narrow, shaders::pt_accumulate, "pt_accumulate", bytes),
                      doctest::Contains(("kernel 'pt_accumulate' takes " + std::to_string(bytes) +
                                         " bytes of push constants").c_str()));
    CHECK_THROWS_WITH(vk::ComputePipeline(narrow, shaders::pt_accumulate, "pt_accumulate", bytes),
                      doctest::Contains("allows 64 (maxPushConstantsSize)"));
    {
        core::Scene scene(narrow, test::sceneOf(test::squareMesh(1.0f)));
        core::PathTracer tracer(narrow);
        tracer.resize({8, 8}, false);
        CHECK_THROWS_WITH(tracer.render(scene, test::lookingDown(2.0f, 2.0f), {}),
                          doctest::Contains("(maxPushConstantsSize)"));
    }

    vk::Context& eight = eightGroupsContext();
    const vk::ComputePipeline accumulate(eight, shaders::pt_accumulate, "pt_accumulate", bytes);
    const gpu::StageParams p{};  // count 0: the kernel returns at once
    CHECK_NOTHROW(eight.submitAndWait([&](VkCommandBuffer cmd) {
        accumulate.bind(cmd);
        accumulate.pushConstants(cmd, &p, bytes);
        accumulate.dispatch(cmd, 8);
    }));
    CHECK_THROWS_WITH(eight.submitAndWait([&](VkCommandBuffer cmd) {
                          accumulate.bind(cmd);
                          accumulate.pushConstants(cmd, &p, bytes);
                          accumulate.dispatch(cmd, 9);
                      }),
                      doctest::Contains("kernel 'pt_accumulate': a dispatch of 9 workgroups exceeds the device's "
                                        "maxComputeWorkGroupCount of 8"));
    // The trace kernels' resume rounds are indirect dispatches the kernels size from the parked rays: the
    // pools hold at most one dispatch's worth.
    CHECK(core::TraceKernels(eight, {.traversal = core::Traversal::Software}).options().resumeCapacity == 8 * 64);
    CHECK(core::TraceKernels(test::testContext(), {.traversal = core::Traversal::Software}).options().resumeCapacity ==
          core::TraceOptions{}.resumeCapacity);
    CHECK(narrow.validationMessageCount() == 0);
    CHECK(eight.validationMessageCount() == 0);
}

// 48x40 pixels at 3 samples: with the device's limits one pass of 5,760 paths in one wave; with 8 workgroups
// per dispatch at most 512 paths fly at once, so each sample is a pass of 4 waves (12 in all), the per-pixel
// stages (accumulate, resolve) run as 4 dispatches each and the trace resume pools hold 512 rays. Random
// numbers are keyed by pixel, sample, bounce and dimension, so colour, depth, albedo and ids must equal the
// unsplit frame's bit for bit, with each traversal back-end the device has. No dispatch may exceed the
// limit (ComputePipeline::dispatch would throw).
TEST_CASE("limits override: a render split to fit 8 workgroups per dispatch equals the unsplit one, bit for bit") {
    test::ValidationGuard guard;
    vk::Context& eight = eightGroupsContext();
    std::vector<core::Traversal> traversals{core::Traversal::Software};
    if (eight.supportsRayQuery()) traversals.push_back(core::Traversal::RayQuery);
    const glm::uvec2 size{48, 40};
    for (const core::Traversal traversal : traversals) {
        CAPTURE(core::traversalName(traversal));
        const test::MixedFrame whole = test::renderMixedFrame(test::testContext(), traversal, size);
        const test::MixedFrame split = test::renderMixedFrame(eight, traversal, size);
        CHECK(whole.stats.waves == 1);
        CHECK(split.stats.waves == 12);
        REQUIRE(whole.color.size() == split.color.size());
        CHECK(std::memcmp(whole.color.data(), split.color.data(), whole.color.size() * sizeof(glm::vec4)) == 0);
        CHECK(std::memcmp(whole.depth.data(), split.depth.data(), whole.depth.size() * sizeof(float)) == 0);
        CHECK(std::memcmp(whole.albedo.data(), split.albedo.data(), whole.albedo.size() * sizeof(float)) == 0);
        CHECK(whole.primitiveIds == split.primitiveIds);
        CHECK(whole.stats.raysTraced == split.stats.raysTraced);
        CHECK(whole.stats.shadowRays == split.stats.shadowRays);
        CHECK(whole.stats.realCollisions == split.stats.realCollisions);
        CHECK(whole.stats.flaggedRays == 0);
        CHECK(split.stats.flaggedRays == 0);
    }
    CHECK(eight.validationMessageCount() == 0);
}
