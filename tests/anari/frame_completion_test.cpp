// Frame behaviour through the public API: KHR_FRAME_COMPLETION_CALLBACK (called once per render, with the
// frame's own handles, when the frame is ready and maps), and frames too large for memory refused at
// render with their size and the bytes they need, every channel counted.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <atomic>
#include <cstdlib>
#include <string>

using ripple::test::RenderSession;

namespace {

struct Completion {
    ANARIDevice device = nullptr;
    ANARIFrame frame = nullptr;
    std::atomic<int> calls{0};
    std::atomic<int> readyInside{-1};
    std::atomic<bool> mapsInside{false};
    std::atomic<bool> handlesMatch{true};
};

void onComplete(const void* userPtr, ANARIDevice device, ANARIFrame frame) {
    auto* c = const_cast<Completion*>(static_cast<const Completion*>(userPtr));
    if (device != c->device || frame != c->frame) c->handlesMatch = false;
    c->readyInside = anariFrameReady(device, frame, ANARI_NO_WAIT);
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(device, frame, "channel.color", &width, &height, &type);
    c->mapsInside = pixels != nullptr && width == 8 && height == 4 && type == ANARI_FLOAT32_VEC4;
    if (pixels) anariUnmapFrame(device, frame, "channel.color");
    ++c->calls;
}

}  // namespace

TEST_CASE("KHR_FRAME_COMPLETION_CALLBACK: called once per render, ready and mappable inside") {
    RenderSession s;
    ANARIWorld world = s.world({s.surface(s.floor(), s.matte({0.8f, 0.8f, 0.8f}))}, {s.directional({0, -1, 0}, 2.0f)});
    ANARIFrame frame = s.frame(world, s.perspective({0, 3, 6}, {0, 0, 0}), s.renderer(1, 2), {8, 4}, ANARI_FLOAT32_VEC4);
    Completion completion;
    completion.device = s.device;
    completion.frame = frame;
    const ANARIFrameCompletionCallback callback = &onComplete;
    s.setRaw(frame, "frameCompletionCallback", ANARI_FRAME_COMPLETION_CALLBACK, &callback);
    // As the ANARI SDK's C++ wrapper passes it: an ANARI_VOID_POINTER parameter's value is the pointer itself.
    s.setRaw(frame, "frameCompletionCallbackUserData", ANARI_VOID_POINTER, &completion);
    s.commit(frame);
    for (int render = 1; render <= 3; ++render) {
        anariRenderFrame(s.device, frame);
        REQUIRE(anariFrameReady(s.device, frame, ANARI_WAIT) == 1);
        CHECK(completion.calls == render);
    }
    CHECK(completion.readyInside == 1);
    CHECK(completion.mapsInside);
    CHECK(completion.handlesMatch);

    // Unset, it is no longer called.
    anariUnsetParameter(s.device, frame, "frameCompletionCallback");
    s.commit(frame);
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    CHECK(completion.calls == 3);
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

// 16384x16384 with every channel: the accumulation, sample radiance and counts, the resolved color and
// every surface channel on the device (16 + 16 + 4 + 16 + 4 + 16 + 16 + 3 * 4 = 100 bytes a pixel), and
// the mapped copies plus one readback on the host (16 + 4 + 12 + 12 + 12 + 16 = 72): at least 172 bytes a
// pixel, 46.2 GB. RIPPLE_MEMORY_LIMIT makes the refusal independent of this machine's memory.
TEST_CASE("a frame too large for memory is refused at render, naming its size and the bytes it needs") {
    setenv("RIPPLE_MEMORY_LIMIT", "8000000000", 1);
    RenderSession s;
    ANARIWorld world = s.world({s.surface(s.floor(), s.matte({0.8f, 0.8f, 0.8f}))}, {});
    ANARIFrame frame = s.frame(world, s.perspective({0, 3, 6}, {0, 0, 0}), s.renderer(1, 2), {16384, 16384},
                               ANARI_FLOAT32_VEC4, true);
    for (const auto& [name, type] : {std::pair{"channel.albedo", ANARI_FLOAT32_VEC3}, {"channel.normal", ANARI_FLOAT32_VEC3},
                                     {"channel.primitiveId", ANARI_UINT32}, {"channel.objectId", ANARI_UINT32},
                                     {"channel.instanceId", ANARI_UINT32}})
        s.setRaw(frame, name, ANARI_DATA_TYPE, &type);
    s.commit(frame);
    anariRenderFrame(s.device, frame);
    REQUIRE(anariFrameReady(s.device, frame, ANARI_WAIT) == 1);
    unsetenv("RIPPLE_MEMORY_LIMIT");
    const std::string log = s.log.dump();
    CHECK_MESSAGE(s.log.count({"cannot render: a 16384x16384 frame with its channels needs ",
                               " but only 8000000000 bytes (7.5 GiB) are available"}) == 1, log);
    const size_t at = log.find("frame with its channels needs ");
    REQUIRE(at != std::string::npos);
    const uint64_t needed = std::stoull(log.substr(at + 30));
    CHECK(needed >= 16384ull * 16384ull * 172ull);
    CHECK(needed < 16384ull * 16384ull * 200ull);  // the paths in flight add a few hundred MB, not more
    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    CHECK(anariMapFrame(s.device, frame, "channel.color", &width, &height, &type) == nullptr);
}
