// The device object behind an ANARIDevice handle. The loaders (Ripple's and the Khronos SDK's) turn every
// device call into a virtual call on it, so its vtable layout (Itanium C++ ABI) is the contract.
#pragma once

#include <cstdint>

#include "anari/anari.h"

namespace ripple::abi {

// Virtual slots are assigned in declaration order; each method takes the C function's arguments minus the
// leading device. Slots: 0 newArray1D ... 38 getProcAddress, 39-40 destructor (complete, deleting), which is
// why the destructor is declared last. This is the layout of Khronos SDK releases 0.14 to 0.16.
// Do not add, remove or reorder virtual functions.
class DeviceInterface {
public:
    using ProcAddress = void (*)(void);

    DeviceInterface() = default;
    DeviceInterface(const DeviceInterface&) = delete;
    DeviceInterface& operator=(const DeviceInterface&) = delete;

    /* 0-2 */
    virtual ANARIArray1D newArray1D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                    ANARIDataType dataType, uint64_t numElements1) = 0;
    virtual ANARIArray2D newArray2D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                    ANARIDataType dataType, uint64_t numElements1, uint64_t numElements2) = 0;
    virtual ANARIArray3D newArray3D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                    ANARIDataType dataType, uint64_t numElements1, uint64_t numElements2,
                                    uint64_t numElements3) = 0;
    /* 3-15 */
    virtual ANARIGeometry newGeometry(const char* type) = 0;
    virtual ANARIMaterial newMaterial(const char* type) = 0;
    virtual ANARISampler newSampler(const char* type) = 0;
    virtual ANARISurface newSurface() = 0;
    virtual ANARISpatialField newSpatialField(const char* type) = 0;
    virtual ANARIVolume newVolume(const char* type) = 0;
    virtual ANARILight newLight(const char* type) = 0;
    virtual ANARIGroup newGroup() = 0;
    virtual ANARIInstance newInstance(const char* type) = 0;
    virtual ANARIWorld newWorld() = 0;
    virtual ANARICamera newCamera(const char* type) = 0;
    virtual ANARIRenderer newRenderer(const char* type) = 0;
    virtual ANARIFrame newFrame() = 0;
    /* 16-25 */
    virtual void setParameter(ANARIObject object, const char* name, ANARIDataType dataType,
                              const void* mem) = 0;
    virtual void unsetParameter(ANARIObject object, const char* name) = 0;
    virtual void unsetAllParameters(ANARIObject object) = 0;
    virtual void* mapParameterArray1D(ANARIObject object, const char* name, ANARIDataType dataType,
                                      uint64_t numElements1, uint64_t* elementStride) = 0;
    virtual void* mapParameterArray2D(ANARIObject object, const char* name, ANARIDataType dataType,
                                      uint64_t numElements1, uint64_t numElements2,
                                      uint64_t* elementStride) = 0;
    virtual void* mapParameterArray3D(ANARIObject object, const char* name, ANARIDataType dataType,
                                      uint64_t numElements1, uint64_t numElements2, uint64_t numElements3,
                                      uint64_t* elementStride) = 0;
    virtual void unmapParameterArray(ANARIObject object, const char* name) = 0;
    virtual void commitParameters(ANARIObject object) = 0;
    virtual void release(ANARIObject object) = 0;
    virtual void retain(ANARIObject object) = 0;
    /* 26-31 */
    virtual void* mapArray(ANARIArray array) = 0;
    virtual void unmapArray(ANARIArray array) = 0;
    virtual int getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,
                            ANARIWaitMask mask) = 0;
    virtual const char** getObjectSubtypes(ANARIDataType objectType) = 0;
    virtual const void* getObjectInfo(ANARIDataType objectType, const char* objectSubtype, const char* infoName,
                                      ANARIDataType infoType) = 0;
    virtual const void* getParameterInfo(ANARIDataType objectType, const char* objectSubtype,
                                         const char* parameterName, ANARIDataType parameterType,
                                         const char* infoName, ANARIDataType infoType) = 0;
    /* 32-36 */
    virtual const void* mapFrame(ANARIFrame frame, const char* channel, uint32_t* width, uint32_t* height,
                                 ANARIDataType* pixelType) = 0;
    virtual void unmapFrame(ANARIFrame frame, const char* channel) = 0;
    virtual void renderFrame(ANARIFrame frame) = 0;
    virtual int frameReady(ANARIFrame frame, ANARIWaitMask mask) = 0;
    virtual void discardFrame(ANARIFrame frame) = 0;
    /* 37-38 */
    virtual ANARIObject newObject(const char* objectType, const char* type) = 0;
    virtual ProcAddress getProcAddress(const char* name) = 0;
    /* 39-40 */
    virtual ~DeviceInterface() = default;
};

// The handle an application holds is the address of the DeviceInterface subobject: a class deriving from
// several bases must convert to DeviceInterface* before making a handle.
inline DeviceInterface* deviceFromHandle(ANARIDevice device) {
    return reinterpret_cast<DeviceInterface*>(device);
}
inline ANARIDevice handleFromDevice(DeviceInterface* device) { return reinterpret_cast<ANARIDevice>(device); }

}  // namespace ripple::abi

// Declares every slot above as an override, for a device class that implements them all in its .cpp
// (Ripple's device and its compositing device): one list, kept beside the slots it mirrors.
#define RIPPLE_ANARI_DEVICE_OVERRIDES                                                                          \
    ANARIArray1D newArray1D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,           \
                            ANARIDataType dataType, uint64_t n1) override;                                     \
    ANARIArray2D newArray2D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,           \
                            ANARIDataType dataType, uint64_t n1, uint64_t n2) override;                        \
    ANARIArray3D newArray3D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,           \
                            ANARIDataType dataType, uint64_t n1, uint64_t n2, uint64_t n3) override;           \
    ANARIGeometry newGeometry(const char* type) override;                                                      \
    ANARIMaterial newMaterial(const char* type) override;                                                      \
    ANARISampler newSampler(const char* type) override;                                                        \
    ANARISurface newSurface() override;                                                                        \
    ANARISpatialField newSpatialField(const char* type) override;                                              \
    ANARIVolume newVolume(const char* type) override;                                                          \
    ANARILight newLight(const char* type) override;                                                            \
    ANARIGroup newGroup() override;                                                                            \
    ANARIInstance newInstance(const char* type) override;                                                      \
    ANARIWorld newWorld() override;                                                                            \
    ANARICamera newCamera(const char* type) override;                                                          \
    ANARIRenderer newRenderer(const char* type) override;                                                      \
    ANARIFrame newFrame() override;                                                                            \
    void setParameter(ANARIObject object, const char* name, ANARIDataType dataType, const void* mem) override;  \
    void unsetParameter(ANARIObject object, const char* name) override;                                        \
    void unsetAllParameters(ANARIObject object) override;                                                      \
    void* mapParameterArray1D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,       \
                              uint64_t* elementStride) override;                                               \
    void* mapParameterArray2D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,       \
                              uint64_t n2, uint64_t* elementStride) override;                                  \
    void* mapParameterArray3D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t n1,       \
                              uint64_t n2, uint64_t n3, uint64_t* elementStride) override;                     \
    void unmapParameterArray(ANARIObject object, const char* name) override;                                   \
    void commitParameters(ANARIObject object) override;                                                        \
    void release(ANARIObject object) override;                                                                 \
    void retain(ANARIObject object) override;                                                                  \
    void* mapArray(ANARIArray array) override;                                                                 \
    void unmapArray(ANARIArray array) override;                                                                \
    int getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,        \
                    ANARIWaitMask mask) override;                                                              \
    const char** getObjectSubtypes(ANARIDataType objectType) override;                                         \
    const void* getObjectInfo(ANARIDataType objectType, const char* objectSubtype, const char* infoName,       \
                              ANARIDataType infoType) override;                                                \
    const void* getParameterInfo(ANARIDataType objectType, const char* objectSubtype, const char* parameterName, \
                                 ANARIDataType parameterType, const char* infoName,                            \
                                 ANARIDataType infoType) override;                                             \
    const void* mapFrame(ANARIFrame frame, const char* channel, uint32_t* width, uint32_t* height,             \
                         ANARIDataType* pixelType) override;                                                   \
    void unmapFrame(ANARIFrame frame, const char* channel) override;                                           \
    void renderFrame(ANARIFrame frame) override;                                                               \
    int frameReady(ANARIFrame frame, ANARIWaitMask mask) override;                                             \
    void discardFrame(ANARIFrame frame) override;                                                              \
    ANARIObject newObject(const char* objectType, const char* type) override;                                  \
    ProcAddress getProcAddress(const char* name) override;
