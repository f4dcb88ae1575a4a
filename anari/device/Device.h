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

    RIPPLE_ANARI_DEVICE_OVERRIDES  // every ANARI device call (anari/backend/DeviceInterface.h)

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
