// The device half of the C API: each function is one virtual call on the ripple::abi::DeviceInterface
// behind the handle. A NULL device is ignored (NULL/0 returned); exceptions never cross the C API.
#include "anari/anari.h"
#include "anari/backend/DeviceInterface.h"
#include "CallGuard.h"

using ripple::abi::DeviceInterface;
using ripple::loader::callGuarded;

namespace {

template <class Result, class Method, class... Args>
Result forward(const char* function, ANARIDevice device, Result fallback, Method method, Args... args) {
    if (device == nullptr) return fallback;
    DeviceInterface* target = ripple::abi::deviceFromHandle(device);
    return callGuarded(function, fallback, [&] { return (target->*method)(args...); });
}

template <class Method, class... Args>
void forwardVoid(const char* function, ANARIDevice device, Method method, Args... args) {
    if (device == nullptr) return;
    DeviceInterface* target = ripple::abi::deviceFromHandle(device);
    callGuarded(function, [&] { (target->*method)(args...); });
}

}  // namespace

ANARIArray1D anariNewArray1D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                             const void* userData, ANARIDataType dataType, uint64_t numElements1) {
    return forward<ANARIArray1D>(__func__, device, nullptr, &DeviceInterface::newArray1D, appMemory, deleter,
                                 userData, dataType, numElements1);
}

ANARIArray2D anariNewArray2D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                             const void* userData, ANARIDataType dataType, uint64_t numElements1,
                             uint64_t numElements2) {
    return forward<ANARIArray2D>(__func__, device, nullptr, &DeviceInterface::newArray2D, appMemory, deleter,
                                 userData, dataType, numElements1, numElements2);
}

ANARIArray3D anariNewArray3D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                             const void* userData, ANARIDataType dataType, uint64_t numElements1,
                             uint64_t numElements2, uint64_t numElements3) {
    return forward<ANARIArray3D>(__func__, device, nullptr, &DeviceInterface::newArray3D, appMemory, deleter,
                                 userData, dataType, numElements1, numElements2, numElements3);
}

void* anariMapArray(ANARIDevice device, ANARIArray array) {
    return forward<void*>(__func__, device, nullptr, &DeviceInterface::mapArray, array);
}

void anariUnmapArray(ANARIDevice device, ANARIArray array) {
    forwardVoid(__func__, device, &DeviceInterface::unmapArray, array);
}

ANARILight anariNewLight(ANARIDevice device, const char* type) {
    return forward<ANARILight>(__func__, device, nullptr, &DeviceInterface::newLight, type);
}

ANARICamera anariNewCamera(ANARIDevice device, const char* type) {
    return forward<ANARICamera>(__func__, device, nullptr, &DeviceInterface::newCamera, type);
}

ANARIGeometry anariNewGeometry(ANARIDevice device, const char* type) {
    return forward<ANARIGeometry>(__func__, device, nullptr, &DeviceInterface::newGeometry, type);
}

ANARISpatialField anariNewSpatialField(ANARIDevice device, const char* type) {
    return forward<ANARISpatialField>(__func__, device, nullptr, &DeviceInterface::newSpatialField, type);
}

ANARIVolume anariNewVolume(ANARIDevice device, const char* type) {
    return forward<ANARIVolume>(__func__, device, nullptr, &DeviceInterface::newVolume, type);
}

ANARISurface anariNewSurface(ANARIDevice device) {
    return forward<ANARISurface>(__func__, device, nullptr, &DeviceInterface::newSurface);
}

ANARIMaterial anariNewMaterial(ANARIDevice device, const char* type) {
    return forward<ANARIMaterial>(__func__, device, nullptr, &DeviceInterface::newMaterial, type);
}

ANARISampler anariNewSampler(ANARIDevice device, const char* type) {
    return forward<ANARISampler>(__func__, device, nullptr, &DeviceInterface::newSampler, type);
}

ANARIGroup anariNewGroup(ANARIDevice device) {
    return forward<ANARIGroup>(__func__, device, nullptr, &DeviceInterface::newGroup);
}

ANARIInstance anariNewInstance(ANARIDevice device, const char* type) {
    return forward<ANARIInstance>(__func__, device, nullptr, &DeviceInterface::newInstance, type);
}

ANARIWorld anariNewWorld(ANARIDevice device) {
    return forward<ANARIWorld>(__func__, device, nullptr, &DeviceInterface::newWorld);
}

ANARIRenderer anariNewRenderer(ANARIDevice device, const char* type) {
    return forward<ANARIRenderer>(__func__, device, nullptr, &DeviceInterface::newRenderer, type);
}

ANARIFrame anariNewFrame(ANARIDevice device) {
    return forward<ANARIFrame>(__func__, device, nullptr, &DeviceInterface::newFrame);
}

ANARIObject anariNewObject(ANARIDevice device, const char* objectType, const char* type) {
    return forward<ANARIObject>(__func__, device, nullptr, &DeviceInterface::newObject, objectType, type);
}

void anariSetParameter(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType dataType,
                       const void* mem) {
    forwardVoid(__func__, device, &DeviceInterface::setParameter, object, name, dataType, mem);
}

void anariUnsetParameter(ANARIDevice device, ANARIObject object, const char* name) {
    forwardVoid(__func__, device, &DeviceInterface::unsetParameter, object, name);
}

void anariUnsetAllParameters(ANARIDevice device, ANARIObject object) {
    forwardVoid(__func__, device, &DeviceInterface::unsetAllParameters, object);
}

void* anariMapParameterArray1D(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType dataType,
                               uint64_t numElements1, uint64_t* elementStride) {
    return forward<void*>(__func__, device, nullptr, &DeviceInterface::mapParameterArray1D, object, name,
                          dataType, numElements1, elementStride);
}

void* anariMapParameterArray2D(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType dataType,
                               uint64_t numElements1, uint64_t numElements2, uint64_t* elementStride) {
    return forward<void*>(__func__, device, nullptr, &DeviceInterface::mapParameterArray2D, object, name,
                          dataType, numElements1, numElements2, elementStride);
}

void* anariMapParameterArray3D(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType dataType,
                               uint64_t numElements1, uint64_t numElements2, uint64_t numElements3,
                               uint64_t* elementStride) {
    return forward<void*>(__func__, device, nullptr, &DeviceInterface::mapParameterArray3D, object, name,
                          dataType, numElements1, numElements2, numElements3, elementStride);
}

void anariUnmapParameterArray(ANARIDevice device, ANARIObject object, const char* name) {
    forwardVoid(__func__, device, &DeviceInterface::unmapParameterArray, object, name);
}

void anariCommitParameters(ANARIDevice device, ANARIObject object) {
    forwardVoid(__func__, device, &DeviceInterface::commitParameters, object);
}

// anariRelease(device, NULL) reaches the device too: ignoring a NULL object is the device's rule to apply.
void anariRelease(ANARIDevice device, ANARIObject object) {
    forwardVoid(__func__, device, &DeviceInterface::release, object);
}

void anariRetain(ANARIDevice device, ANARIObject object) {
    forwardVoid(__func__, device, &DeviceInterface::retain, object);
}

const char** anariGetObjectSubtypes(ANARIDevice device, ANARIDataType objectType) {
    return forward<const char**>(__func__, device, nullptr, &DeviceInterface::getObjectSubtypes, objectType);
}

const void* anariGetObjectInfo(ANARIDevice device, ANARIDataType objectType, const char* objectSubtype,
                               const char* infoName, ANARIDataType infoType) {
    return forward<const void*>(__func__, device, nullptr, &DeviceInterface::getObjectInfo, objectType,
                                objectSubtype, infoName, infoType);
}

const void* anariGetParameterInfo(ANARIDevice device, ANARIDataType objectType, const char* objectSubtype,
                                  const char* parameterName, ANARIDataType parameterType, const char* infoName,
                                  ANARIDataType infoType) {
    return forward<const void*>(__func__, device, nullptr, &DeviceInterface::getParameterInfo, objectType,
                                objectSubtype, parameterName, parameterType, infoName, infoType);
}

int anariGetProperty(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType type, void* mem,
                     uint64_t size, ANARIWaitMask mask) {
    return forward<int>(__func__, device, 0, &DeviceInterface::getProperty, object, name, type, mem, size, mask);
}

const void* anariMapFrame(ANARIDevice device, ANARIFrame frame, const char* channel, uint32_t* width,
                          uint32_t* height, ANARIDataType* pixelType) {
    return forward<const void*>(__func__, device, nullptr, &DeviceInterface::mapFrame, frame, channel, width,
                                height, pixelType);
}

void anariUnmapFrame(ANARIDevice device, ANARIFrame frame, const char* channel) {
    forwardVoid(__func__, device, &DeviceInterface::unmapFrame, frame, channel);
}

void anariRenderFrame(ANARIDevice device, ANARIFrame frame) {
    forwardVoid(__func__, device, &DeviceInterface::renderFrame, frame);
}

int anariFrameReady(ANARIDevice device, ANARIFrame frame, ANARIWaitMask mask) {
    return forward<int>(__func__, device, 0, &DeviceInterface::frameReady, frame, mask);
}

void anariDiscardFrame(ANARIDevice device, ANARIFrame frame) {
    forwardVoid(__func__, device, &DeviceInterface::discardFrame, frame);
}

void (*anariDeviceGetProcAddress(ANARIDevice device, const char* name))(void) {
    return forward<DeviceInterface::ProcAddress>(__func__, device, nullptr, &DeviceInterface::getProcAddress,
                                                 name);
}
