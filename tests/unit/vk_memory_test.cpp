// Discrete-memory mode (vk::ContextOptions::discreteMemory): device buffers are never mapped, every upload and
// download goes through a staging buffer, as on a discrete GPU, and the path tracer renders the image of the
// mapped mode bit for bit.
#include "core/render/PathTracer.h"
#include "tests/support/MixedFrame.h"

#include <doctest/doctest.h>

#include <cstring>
#include <numeric>
#include <vector>

using namespace ripple;

namespace {

// A context of its own in discrete-memory mode, validated like the shared one.
vk::Context& discreteContext() {
    static vk::Context context([] {
        vk::ContextOptions options = test::testContextOptions();
        options.printDeviceChoice = false;
        options.discreteMemory = true;
        return options;
    }());
    return context;
}

std::vector<uint8_t> pattern(size_t bytes, uint32_t seed) {
    std::vector<uint8_t> out(bytes);
    uint32_t x = seed * 2654435761u + 1u;
    for (uint8_t& b : out) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        b = static_cast<uint8_t>(x >> 24);
    }
    return out;
}

}  // namespace

// Buffers of sizes around the word and page sizes, written and read at offsets that are not multiples of 4,
// over a background pattern: every byte read back must be the one written there, neighbours untouched.
// Each transfer must have gone through staging (one count each), and only HostStaging buffers are mapped.
TEST_CASE("discrete-memory mode: uploads and downloads go through staging, bit-exactly") {
    vk::Context& context = discreteContext();
    REQUIRE(context.discreteMemoryMode());
    CHECK_FALSE(context.mapsDeviceMemory());
    for (const size_t bytes : {size_t(1), size_t(3), size_t(4), size_t(255), size_t(4096), size_t(65537),
                               size_t((1 << 20) + 7)}) {
        for (const size_t offset : {size_t(0), size_t(1), size_t(13), size_t(4096)}) {
            CAPTURE(bytes);
            CAPTURE(offset);
            const size_t total = offset + bytes + 29;
            vk::Buffer buffer(context, total, "staged test buffer");
            CHECK_FALSE(buffer.isMapped());
            const uint64_t before = context.stagedTransferCount();
            std::vector<uint8_t> expected = pattern(total, uint32_t(bytes + offset));
            buffer.upload(expected.data(), total);
            const std::vector<uint8_t> written = pattern(bytes, uint32_t(7 * bytes + offset + 1));
            buffer.upload(written.data(), bytes, offset);
            std::copy(written.begin(), written.end(), expected.begin() + std::ptrdiff_t(offset));
            std::vector<uint8_t> whole(total), part(bytes);
            buffer.download(whole.data(), total);
            buffer.download(part.data(), bytes, offset);
            CHECK(whole == expected);
            CHECK(part == written);
            CHECK(context.stagedTransferCount() - before == 4);
        }
    }
    vk::Buffer host(context, 64, "host staging test buffer", 0, vk::Buffer::Placement::HostStaging);
    CHECK(host.isMapped());
    const uint64_t before = context.stagedTransferCount();
    const std::vector<uint8_t> bytes = pattern(64, 5);
    std::vector<uint8_t> back(64);
    host.upload(bytes.data(), 64);
    host.download(back.data(), 64);
    CHECK(back == bytes);
    CHECK(context.stagedTransferCount() == before);
    // The shared context maps where the device's memory is host-visible; its transfers are never staged then.
    vk::Buffer mapped(test::testContext(), 64, "mapped test buffer");
    CHECK(mapped.isMapped() == test::testContext().mapsDeviceMemory());
    CHECK(context.validationMessageCount() == 0);
}

// The same scene, camera and settings on the shared context (mapped device memory on a CPU device) and on a
// context in discrete-memory mode: colour, depth, albedo and ids equal bit for bit, with each traversal
// back-end the device has (the ray-query one uploads its acceleration structures' inputs too). The render
// in discrete mode must have staged its transfers (scene, frame constants, read-backs).
TEST_CASE("discrete-memory mode: the path tracer renders the mapped mode's image, bit for bit") {
    test::ValidationGuard guard;
    vk::Context& discrete = discreteContext();
    std::vector<core::Traversal> traversals{core::Traversal::Software};
    if (discrete.supportsRayQuery()) traversals.push_back(core::Traversal::RayQuery);
    for (const core::Traversal traversal : traversals) {
        CAPTURE(core::traversalName(traversal));
        const test::MixedFrame mapped = test::renderMixedFrame(test::testContext(), traversal);
        const uint64_t before = discrete.stagedTransferCount();
        const test::MixedFrame staged = test::renderMixedFrame(discrete, traversal);
        CHECK(discrete.stagedTransferCount() - before > 10);
        REQUIRE(mapped.color.size() == staged.color.size());
        CHECK(std::memcmp(mapped.color.data(), staged.color.data(), mapped.color.size() * sizeof(glm::vec4)) == 0);
        CHECK(std::memcmp(mapped.depth.data(), staged.depth.data(), mapped.depth.size() * sizeof(float)) == 0);
        CHECK(std::memcmp(mapped.albedo.data(), staged.albedo.data(), mapped.albedo.size() * sizeof(float)) == 0);
        CHECK(mapped.primitiveIds == staged.primitiveIds);
        CHECK(mapped.stats.raysTraced == staged.stats.raysTraced);
        CHECK(mapped.stats.realCollisions == staged.stats.realCollisions);
        // Not a blank image: the floor, the balls and the medium all show.
        CHECK(mapped.stats.realCollisions > 0);
        const float sum = std::accumulate(mapped.color.begin(), mapped.color.end(), 0.0f,
                                          [](float s, const glm::vec4& c) { return s + c.r + c.g + c.b; });
        CHECK(sum > 0.0f);
    }
    CHECK(discrete.validationMessageCount() == 0);
}
