// The Ripple ANARI device: the object behind an ANARIDevice handle. Every API call arrives here as a
// virtual call (the slot order is in anari/backend/DeviceInterface.h), is checked, and is forwarded to
// the object it names. Nothing throws across this boundary: failures become status messages.
#pragma once

#include "anari/backend/DeviceInterface.h"
#include "anari/device/object/DeviceState.h"

#include <map>
#include <string>
#include <utility>

namespace ripple::device {

class Object;
class Array;
class Frame;

class Device final : public abi::DeviceInterface {
public:
    Device(const char* subtype, ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr);
    ~Device() override;

    ANARIDevice handle() { return abi::handleFromDevice(this); }

    ANARIArray1D newArray1D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t n1) override;
    ANARIArray2D newArray2D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t n1, uint64_t n2) override;
    ANARIArray3D newArray3D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t n1, uint64_t n2, uint64_t n3) override;
    ANARIGeometry newGeometry(const char* type) override;
    ANARIMaterial newMaterial(const char* type) override;
    ANARISampler newSampler(const char* type) override;
    ANARISurface newSurface() override;
    ANARISpatialField newSpatialField(const char* type) override;
    ANARIVolume newVolume(const char* type) override;
    ANARILight newLight(const char* type) override;
    ANARIGroup newGroup() override;
    ANARIInstance newInstance(const char* type) override;
    ANARIWorld newWorld() override;
    ANARICamera newCamera(const char* type) override;
    ANARIRenderer newRenderer(const char* type) override;
    ANARIFrame newFrame() override;
    void setParameter(ANARIObject object, const char* name, ANARIDataType dataType, const void* mem) override;
    void unsetParameter(ANARIObject object, const char* name) override;
    void unsetAllParameters(ANARIObject object) override;
    void* mapParameterArray1D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,
                              uint64_t* elementStride) override;
    void* mapParameterArray2D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,
                              uint64_t n2, uint64_t* elementStride) override;
    void* mapParameterArray3D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,
                              uint64_t n2, uint64_t n3, uint64_t* elementStride) override;
    void unmapParameterArray(ANARIObject object, const char* name) override;
    void commitParameters(ANARIObject object) override;
    void release(ANARIObject object) override;
    void retain(ANARIObject object) override;
    void* mapArray(ANARIArray array) override;
    void unmapArray(ANARIArray array) override;
    int getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,
                    ANARIWaitMask mask) override;
    const char** getObjectSubtypes(ANARIDataType objectType) override;
    const void* getObjectInfo(ANARIDataType objectType, const char* objectSubtype, const char* infoName,
                              ANARIDataType infoType) override;
    const void* getParameterInfo(ANARIDataType objectType, const char* objectSubtype, const char* parameterName,
                                 ANARIDataType parameterType, const char* infoName,
                                 ANARIDataType infoType) override;
    const void* mapFrame(ANARIFrame frame, const char* channel, uint32_t* width, uint32_t* height,
                         ANARIDataType* pixelType) override;
    void unmapFrame(ANARIFrame frame, const char* channel) override;
    void renderFrame(ANARIFrame frame) override;
    int frameReady(ANARIFrame frame, ANARIWaitMask mask) override;
    void discardFrame(ANARIFrame frame) override;
    ANARIObject newObject(const char* objectType, const char* type) override;
    ProcAddress getProcAddress(const char* name) override;

private:
    bool isDevice(ANARIObject object) const;
    // The object behind a handle, or nullptr (reported, naming the call) for NULL.
    // The object behind a handle the application passed, or nullptr (reported, naming the call) for NULL,
    // a handle that is not a live object of this device, or one the application has released.
    Object* objectFrom(ANARIObject handle, const char* call);
    Array* arrayFrom(ANARIArray handle, const char* call);
    Frame* frameFrom(ANARIFrame handle, const char* call);
    ANARIObject create(ANARIDataType type, const char* subtype, const char* call);
    ANARIArray newArray(ANARIDataType arrayType, const void* appMemory, ANARIMemoryDeleter deleter,
                        const void* userData, ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3);
    void* mapParameterArray(ANARIObject object, const char* name, ANARIDataType arrayType,
                            ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3,
                            uint64_t* elementStride);
    void setDeviceParameter(const char* name, ANARIDataType type, const void* mem);
    void destroyRemainingObjects();
    // Runs body, turning any exception into an ERROR status message naming the call.
    template <class Body> auto guarded(const char* call, Body&& body) -> decltype(body());

    std::string subtype_;
    DeviceState state_;
    uint32_t references_ = 1;
    ANARIStatusCallback pendingCallback_ = nullptr;  // device parameters take effect at commit
    const void* pendingCallbackUserPtr_ = nullptr;
    bool callbackSet_ = false;
    // Arrays handed out by anariMapParameterArray*, until anariUnmapParameterArray.
    std::map<std::pair<Object*, std::string>, Array*> parameterArrays_;
};

}  // namespace ripple::device
