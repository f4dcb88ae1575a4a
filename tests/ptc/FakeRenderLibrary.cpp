// A device library that "renders" known colors and depths (FakeRender.h) so that the compositing device's
// result can be checked exactly; it knows nothing of MPI: its rank arrives as the device parameter fakeRank.
#include "FakeRender.h"

#include "anari/backend/DeviceInterface.h"
#include "anari/backend/LibraryInterface.h"

#include <cstring>
#include <map>
#include <string>
#include <vector>

using ripple::abi::DeviceInterface;
using ripple::abi::LibraryInterface;

namespace {

struct FakeFrame {
    uint32_t width = 0, height = 0;
    std::vector<float> color, depth;
    int references = 1;
};

// Handles of objects this double does not model: distinct, never dereferenced.
template <class Handle>
Handle dummy() {
    static char storage;
    return reinterpret_cast<Handle>(&storage);
}

class FakeRenderDevice final : public DeviceInterface {
public:
    FakeRenderDevice(ANARIStatusCallback callback, const void* userPtr) : callback_(callback), userPtr_(userPtr) {}

    ANARIArray1D newArray1D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t) override { return dummy<ANARIArray1D>(); }
    ANARIArray2D newArray2D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t, uint64_t) override { return dummy<ANARIArray2D>(); }
    ANARIArray3D newArray3D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t, uint64_t, uint64_t) override { return dummy<ANARIArray3D>(); }
    ANARIGeometry newGeometry(const char*) override { return dummy<ANARIGeometry>(); }
    ANARIMaterial newMaterial(const char*) override { return dummy<ANARIMaterial>(); }
    ANARISampler newSampler(const char*) override { return dummy<ANARISampler>(); }
    ANARISurface newSurface() override { return dummy<ANARISurface>(); }
    ANARISpatialField newSpatialField(const char*) override { return dummy<ANARISpatialField>(); }
    ANARIVolume newVolume(const char*) override { return dummy<ANARIVolume>(); }
    ANARILight newLight(const char*) override { return dummy<ANARILight>(); }
    ANARIGroup newGroup() override { return dummy<ANARIGroup>(); }
    ANARIInstance newInstance(const char*) override { return dummy<ANARIInstance>(); }
    ANARIWorld newWorld() override { return dummy<ANARIWorld>(); }
    ANARICamera newCamera(const char*) override { return dummy<ANARICamera>(); }
    ANARIRenderer newRenderer(const char*) override { return dummy<ANARIRenderer>(); }
    ANARIFrame newFrame() override {
        auto* frame = new FakeFrame;
        frames_[reinterpret_cast<ANARIObject>(frame)] = true;
        return reinterpret_cast<ANARIFrame>(frame);
    }

    void setParameter(ANARIObject object, const char* name, ANARIDataType type, const void* mem) override {
        const std::string key = name;
        if (isDevice(object) && key == "fakeRank" && type == ANARI_INT32) std::memcpy(&rank_, mem, sizeof(rank_));
        if (isDevice(object) && key == "mpiCommunicator") communicatorGiven_ = true;
        if (FakeFrame* frame = frameOf(object); frame && key == "size" && type == ANARI_UINT32_VEC2) {
            std::memcpy(&frame->width, mem, 4);
            std::memcpy(&frame->height, static_cast<const char*>(mem) + 4, 4);
        }
    }
    void unsetParameter(ANARIObject, const char*) override {}
    void unsetAllParameters(ANARIObject) override {}
    void* mapParameterArray1D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t*) override { return nullptr; }
    void* mapParameterArray2D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t, uint64_t*) override { return nullptr; }
    void* mapParameterArray3D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t, uint64_t, uint64_t*) override { return nullptr; }
    void unmapParameterArray(ANARIObject, const char*) override {}
    void commitParameters(ANARIObject) override {}
    void release(ANARIObject object) override {
        if (isDevice(object)) {
            delete this;
            return;
        }
        if (FakeFrame* frame = frameOf(object); frame && --frame->references == 0) {
            frames_.erase(object);
            delete frame;
        }
    }
    void retain(ANARIObject object) override {
        if (FakeFrame* frame = frameOf(object)) ++frame->references;
    }
    void* mapArray(ANARIArray) override { return nullptr; }
    void unmapArray(ANARIArray) override {}
    int getProperty(ANARIObject, const char*, ANARIDataType, void*, uint64_t, ANARIWaitMask) override { return 0; }
    const char** getObjectSubtypes(ANARIDataType) override { return nullptr; }
    const void* getObjectInfo(ANARIDataType, const char*, const char*, ANARIDataType) override { return nullptr; }
    const void* getParameterInfo(ANARIDataType, const char*, const char*, ANARIDataType, const char*, ANARIDataType) override { return nullptr; }

    const void* mapFrame(ANARIFrame handle, const char* channel, uint32_t* width, uint32_t* height,
                         ANARIDataType* type) override {
        FakeFrame* frame = frameOf(reinterpret_cast<ANARIObject>(handle));
        if (!frame) return nullptr;
        *width = frame->width;
        *height = frame->height;
        const std::string name = channel;
        *type = name == "channel.color" ? ANARI_FLOAT32_VEC4 : ANARI_FLOAT32;
        return name == "channel.color" ? frame->color.data() : frame->depth.data();
    }
    void unmapFrame(ANARIFrame, const char*) override {}
    void renderFrame(ANARIFrame handle) override {
        FakeFrame* frame = frameOf(reinterpret_cast<ANARIObject>(handle));
        frame->color.resize(size_t(frame->width) * frame->height * 4);
        frame->depth.resize(size_t(frame->width) * frame->height);
        for (uint32_t y = 0; y < frame->height; ++y)
            for (uint32_t x = 0; x < frame->width; ++x) {
                const fakerender::Fragment f = fakerender::fragment(x, y, rank_);
                const size_t p = size_t(y) * frame->width + x;
                std::memcpy(&frame->color[p * 4], f.rgba, sizeof(f.rgba));
                frame->depth[p] = f.depth;
            }
        if (callback_) {
            const std::string message = std::string(fakerender::kRenderedMessage) + (communicatorGiven_ ? " alone" : "");
            callback_(userPtr_, reinterpret_cast<ANARIDevice>(this), nullptr, ANARI_DEVICE, ANARI_SEVERITY_WARNING,
                      ANARI_STATUS_NO_ERROR, message.c_str());
        }
    }
    int frameReady(ANARIFrame, ANARIWaitMask) override { return 1; }
    void discardFrame(ANARIFrame) override {}
    ANARIObject newObject(const char*, const char*) override { return dummy<ANARIObject>(); }
    ProcAddress getProcAddress(const char*) override { return nullptr; }

private:
    bool isDevice(ANARIObject object) const { return static_cast<const void*>(object) == static_cast<const DeviceInterface*>(this); }
    FakeFrame* frameOf(ANARIObject object) {
        return frames_.count(object) ? reinterpret_cast<FakeFrame*>(object) : nullptr;
    }

    ANARIStatusCallback callback_;
    const void* userPtr_;
    int32_t rank_ = 0;
    bool communicatorGiven_ = false;
    std::map<ANARIObject, bool> frames_;
};

class FakeRenderLibrary final : public LibraryInterface {
public:
    FakeRenderLibrary(void* handle, ANARIStatusCallback callback, const void* userPtr)
        : LibraryInterface(handle, callback, userPtr) {}
    ANARIDevice newDevice(const char*) override {
        auto* device = new FakeRenderDevice(defaultStatusCallback, defaultStatusCallbackUserPtr);
        return reinterpret_cast<ANARIDevice>(static_cast<DeviceInterface*>(device));
    }
    ANARIDevice newInitializedDevice(const char* subtype, ANARIParameterValue*) override { return newDevice(subtype); }
    const char** getDeviceExtensions(const char*) override { return nullptr; }
    const char** getDeviceSubtypes() override { return nullptr; }
    void loadModule(const char*) override {}
    void unloadModule(const char*) override {}
};

}  // namespace

extern "C" __attribute__((visibility("default"))) ANARILibrary anari_library_ptcfake_new_library(
    void* dlopenHandle, ANARIStatusCallback callback, const void* userPtr) {
    return reinterpret_cast<ANARILibrary>(static_cast<LibraryInterface*>(new FakeRenderLibrary(dlopenHandle, callback, userPtr)));
}
