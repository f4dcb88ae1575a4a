// The pass-through compositing device under mpirun: wrapping the test double (FakeRender.h), rank 0's
// frame must equal, exactly, the depth-sorted premultiplied blend of every rank's fragments; a wrapped
// library that does not exist must be reported, not crash.
#include "FakeRender.h"
#include "mpi/Communicator.h"

#include "anari/anari.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace {

struct Messages {
    std::vector<std::string> texts;
    bool contains(const std::string& part) const {
        return std::any_of(texts.begin(), texts.end(), [&](const std::string& t) { return t.find(part) != std::string::npos; });
    }
};

void record(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity, ANARIStatusCode,
            const char* message) {
    if (severity <= ANARI_SEVERITY_WARNING) static_cast<Messages*>(const_cast<void*>(userPtr))->texts.push_back(message);
}

// What compositing must give for pixel (x, y): fragments in rank order, background only from rank 0,
// stably sorted by depth, blended front to back (premultiplied).
fakerender::Fragment expected(uint32_t x, uint32_t y, int ranks) {
    std::vector<fakerender::Fragment> fragments;
    for (int r = 0; r < ranks; ++r) {
        const fakerender::Fragment f = fakerender::fragment(x, y, r);
        if (std::isinf(f.depth) && (r != 0 || f.rgba[3] == 0.0f)) continue;
        fragments.push_back(f);
    }
    std::stable_sort(fragments.begin(), fragments.end(),
                     [](const fakerender::Fragment& a, const fakerender::Fragment& b) { return a.depth < b.depth; });
    fakerender::Fragment out{{0.0f, 0.0f, 0.0f, 0.0f}, INFINITY};
    for (const fakerender::Fragment& f : fragments) {
        const float transmitted = 1.0f - out.rgba[3];
        for (int c = 0; c < 4; ++c) out.rgba[c] += transmitted * f.rgba[c];
        out.depth = std::min(out.depth, f.depth);
    }
    return out;
}

// ripple_ptc's device wrapping the test double, told this process's rank; not yet committed.
ANARIDevice ptcOverFake(ANARILibrary library, int32_t rank) {
    ANARIDevice device = anariNewDevice(library, "default");
    REQUIRE(device != nullptr);
    anariSetParameter(device, device, "library", ANARI_STRING, "ptcfake");
    anariSetParameter(device, device, "fakeRank", ANARI_INT32, &rank);
    return device;
}

}  // namespace

TEST_CASE("ripple_ptc composites the test double's fragments exactly") {
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    Messages messages;
    ANARILibrary library = anariLoadLibrary("ripple_ptc", record, &messages);
    REQUIRE(library != nullptr);
    ANARIDevice device = ptcOverFake(library, ranks.rank());
    anariCommitParameters(device, device);

    const uint32_t size[2] = {7, 5};  // 5 rows over up to 3 ranks: bands of unequal height
    ANARIFrame frame = anariNewFrame(device);
    REQUIRE(frame != nullptr);
    const ANARIDataType colorType = ANARI_FLOAT32_VEC4, depthType = ANARI_FLOAT32;
    anariSetParameter(device, frame, "size", ANARI_UINT32_VEC2, size);
    anariSetParameter(device, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    anariSetParameter(device, frame, "channel.depth", ANARI_DATA_TYPE, &depthType);
    anariCommitParameters(device, frame);
    anariRenderFrame(device, frame);
    anariFrameReady(device, frame, ANARI_WAIT);

    // The wrapped device's status message reached the application's callback; with MPI it was told to
    // render alone (MPI_COMM_SELF).
    CHECK(messages.contains(fakerender::kRenderedMessage));
    if (ripple::mpi::mpiActive()) CHECK(messages.contains(std::string(fakerender::kRenderedMessage) + " alone"));

    uint32_t width = 0, height = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    const auto* color = static_cast<const float*>(anariMapFrame(device, frame, "channel.color", &width, &height, &type));
    if (ranks.rank() == 0) {
        REQUIRE(color != nullptr);
        CHECK(width == size[0]);
        CHECK(height == size[1]);
        CHECK(type == ANARI_FLOAT32_VEC4);
        int wrong = 0;
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) {
                const fakerender::Fragment want = expected(x, y, ranks.size());
                for (int c = 0; c < 4; ++c) wrong += color[(y * size[0] + x) * 4 + uint32_t(c)] != want.rgba[c];
            }
        CHECK(wrong == 0);  // exact: every value is dyadic
        anariUnmapFrame(device, frame, "channel.color");
        const auto* depth = static_cast<const float*>(anariMapFrame(device, frame, "channel.depth", &width, &height, &type));
        REQUIRE(depth != nullptr);
        int wrongDepth = 0;
        for (uint32_t y = 0; y < size[1]; ++y)
            for (uint32_t x = 0; x < size[0]; ++x) wrongDepth += depth[y * size[0] + x] != expected(x, y, ranks.size()).depth;
        CHECK(wrongDepth == 0);
        anariUnmapFrame(device, frame, "channel.depth");
    } else {
        CHECK(color == nullptr);  // only rank 0 holds the composited image
    }

    // A frame the application retained keeps its compositing state past the first release.
    anariRetain(device, frame);
    anariRelease(device, frame);
    messages.texts.clear();
    anariRenderFrame(device, frame);
    anariFrameReady(device, frame, ANARI_WAIT);
    CHECK_MESSAGE(!messages.contains("not a frame of this device"), "the retained frame lost its state");
    if (ranks.rank() == 0) {
        color = static_cast<const float*>(anariMapFrame(device, frame, "channel.color", &width, &height, &type));
        CHECK(color != nullptr);
        if (color) anariUnmapFrame(device, frame, "channel.color");
    }
    anariRelease(device, frame);
    anariRelease(device, device);
    anariUnloadLibrary(library);
}

// The device parameter "compositing": every method the rank count allows composites the same fragments
// exactly, and the frame names the method it composited with.
TEST_CASE("ripple_ptc composites with the method the device parameter names") {
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    const bool powerOfTwo = (ranks.size() & (ranks.size() - 1)) == 0;
    std::vector<const char*> methods = {"directSend", "radixK", "auto"};
    if (powerOfTwo) methods.push_back("binarySwap");
    for (const char* method : methods) {
        CAPTURE(method);
        Messages messages;
        ANARILibrary library = anariLoadLibrary("ripple_ptc", record, &messages);
        REQUIRE(library != nullptr);
        ANARIDevice device = ptcOverFake(library, ranks.rank());
        anariSetParameter(device, device, "compositing", ANARI_STRING, method);
        anariCommitParameters(device, device);
        const uint32_t size[2] = {7, 5};
        ANARIFrame frame = anariNewFrame(device);
        const ANARIDataType colorType = ANARI_FLOAT32_VEC4;
        anariSetParameter(device, frame, "size", ANARI_UINT32_VEC2, size);
        anariSetParameter(device, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
        anariCommitParameters(device, frame);
        anariRenderFrame(device, frame);
        anariFrameReady(device, frame, ANARI_WAIT);
        const char* used = nullptr;
        CHECK(anariGetProperty(device, frame, "ripple.compositing", ANARI_STRING, &used, sizeof(used), ANARI_WAIT) == 1);
        CHECK(std::string(used ? used : "") == method);
        uint32_t width = 0, height = 0;
        ANARIDataType type = ANARI_UNKNOWN;
        const auto* color = static_cast<const float*>(anariMapFrame(device, frame, "channel.color", &width, &height, &type));
        if (ranks.rank() == 0) {
            REQUIRE(color != nullptr);
            int wrong = 0;
            for (uint32_t y = 0; y < size[1]; ++y)
                for (uint32_t x = 0; x < size[0]; ++x)
                    for (int c = 0; c < 4; ++c)
                        wrong += color[(y * size[0] + x) * 4 + uint32_t(c)] != expected(x, y, ranks.size()).rgba[c];
            CHECK(wrong == 0);
            anariUnmapFrame(device, frame, "channel.color");
        }
        CHECK_FALSE(messages.contains("compositing"));  // no error about the method
        anariRelease(device, frame);
        anariRelease(device, device);
        anariUnloadLibrary(library);
    }
}

TEST_CASE("ripple_ptc reports a wrapped library that does not exist") {
    Messages messages;
    ANARILibrary library = anariLoadLibrary("ripple_ptc", record, &messages);
    REQUIRE(library != nullptr);
    ANARIDevice device = anariNewDevice(library, "default");
    REQUIRE(device != nullptr);
    anariSetParameter(device, device, "library", ANARI_STRING, "nosuchdevice");
    anariCommitParameters(device, device);
    CHECK(anariNewFrame(device) == nullptr);
    CHECK(anariNewWorld(device) == nullptr);
    CHECK(messages.contains("cannot load the wrapped library 'nosuchdevice'"));
    anariRelease(device, device);
    anariUnloadLibrary(library);
}

TEST_CASE("ripple_ptc reports the wrapped device's extensions, less the channels it cannot composite") {
    auto contains = [](const char** list, const std::string& name) {
        for (; list && *list; ++list)
            if (name == *list) return true;
        return false;
    };
    Messages messages;
    ANARILibrary library = anariLoadLibrary("ripple_ptc", record, &messages);
    REQUIRE(library != nullptr);
    // The library-level list asks the default wrapped library, Ripple.
    const char** fromLibrary = anariGetDeviceExtensions(library, "default");
    ANARIDevice device = anariNewDevice(library, "default");
    REQUIRE(device != nullptr);
    anariSetParameter(device, device, "library", ANARI_STRING, "ripple");
    anariCommitParameters(device, device);
    const char** fromDevice = nullptr;
    REQUIRE(anariGetProperty(device, device, "extension", ANARI_STRING_LIST, &fromDevice, sizeof(fromDevice),
                             ANARI_WAIT) == 1);
    for (const char** list : {fromLibrary, fromDevice}) {
        CHECK(contains(list, "ANARI_KHR_GEOMETRY_TRIANGLE"));
        CHECK(contains(list, "ANARI_KHR_CAMERA_PERSPECTIVE"));
        CHECK(contains(list, "ANARI_KHR_MATERIAL_MATTE"));
        CHECK(contains(list, "ANARI_KHR_DATA_PARALLEL_MPI"));
        CHECK_FALSE(contains(list, "ANARI_KHR_FRAME_CHANNEL_ALBEDO"));
        CHECK_FALSE(contains(list, "ANARI_KHR_FRAME_COMPLETION_CALLBACK"));
    }
    CHECK(fromLibrary == fromDevice);  // the same list, interned
    CHECK(messages.texts.empty());
    anariRelease(device, device);
    anariUnloadLibrary(library);
}
