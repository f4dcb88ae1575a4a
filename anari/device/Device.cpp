// The Ripple device's API entry points: argument checks, object creation through the factory, parameter
// and reference handling, and forwarding to arrays and frames. Every entry point is guarded: an exception
// becomes an ERROR status message and a neutral return value.
#include "anari/device/Device.h"

#include "anari/device/Introspection.h"
#include "anari/device/ObjectFactory.h"
#include "anari/device/array/Array.h"
#include "anari/device/frame/Frame.h"
#include "anari/device/object/Object.h"
#include "core/render/Traversal.h"
#include "core/vk/Context.h"

#include <cstdio>
#include <cstring>
#include <exception>

namespace ripple::device {

namespace {

constexpr int32_t kDeviceVersion = 1;  // the "version" property

template <class Handle> Handle handleOf(Object* object) { return reinterpret_cast<Handle>(object->handle()); }

bool isArrayType(ANARIDataType type) {
    return type == ANARI_ARRAY1D || type == ANARI_ARRAY2D || type == ANARI_ARRAY3D;
}

std::string handleText(const void* handle) {
    char text[32];
    std::snprintf(text, sizeof(text), "%p", handle);
    return text;
}

}  // namespace

Device::Device(const char* subtype, ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr)
    : subtype_(subtype ? subtype : "default"), state_(handle(), defaultCallback, defaultCallbackUserPtr) {}

Device::~Device() {
    state_.waitForWork();  // frames still rendering use state_ and its Vulkan context
    try {
        // The device's last release is collective in data-parallel ANARI; a peer that never arrives (it
        // failed elsewhere) ends every rank rather than leaving this one blocked forever. Generous: rank 0
        // may still be writing a large image while the others wait here.
        state_.communicator().barrierOrAbort(600.0, "device release: a rank did not release its device within "
                                                    "600 s (it failed or is stuck); ending every rank");
    } catch (const std::exception& error) {
        state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_UNKNOWN_ERROR,
                      std::string("device release: ") + error.what());
    }
    for (auto& [key, array] : parameterArrays_) array->releasePublic();
    destroyRemainingObjects();
}

void Device::destroyRemainingObjects() {
    // Objects the application never released are reported; then every live object lets go of what it holds
    // (which frees reference cycles), and what is left is held by the application alone and deleted, frames
    // and parents first so that their children's counts fall in turn. Nothing outlives the device's state.
    std::vector<Object*> live = state_.handles.liveObjects();
    size_t leaked = 0;
    for (Object* object : live) leaked += object->publicReferenceCount() > 0 ? 1 : 0;
    if (leaked > 0)
        state_.report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_NO_ERROR,
                      "device released with " + std::to_string(leaked) +
                          " object(s) still alive (not released by the application)");
    for (Object* object : live) object->retain();
    for (Object* object : live) object->dropReferences();
    for (Object* object : live) object->release();
    // Deleting one object may delete others: work from handles, which tell whether an object still lives.
    std::vector<ANARIObject> handles;
    for (Object* object : state_.handles.liveObjects()) handles.push_back(object->handle());
    for (bool progress = true; progress;) {
        progress = false;
        for (ANARIObject handle : handles) {
            Object* object = state_.handles.find(handle);
            if (!object || object->referenceCount() != object->publicReferenceCount()) continue;
            delete object;
            progress = true;
        }
    }
}

template <class Body> auto Device::guarded(const char* call, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const std::exception& error) {
        state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_UNKNOWN_ERROR,
                      std::string(call) + ": " + error.what());
    } catch (...) {
        state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_UNKNOWN_ERROR,
                      std::string(call) + ": unknown exception");
    }
    if constexpr (!std::is_void_v<decltype(body())>) return {};
}

bool Device::isDevice(ANARIObject object) const {
    return reinterpret_cast<const void*>(object) == static_cast<const abi::DeviceInterface*>(this);
}

Object* Device::objectFrom(ANARIObject handle, const char* call) {
    if (!handle) {
        state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                      std::string(call) + ": NULL object handle");
        return nullptr;
    }
    Object* object = state_.handles.find(handle);
    if (!object) {
        state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                      std::string(call) + ": handle " + handleText(handle) +
                          " is not a live object of this device (released already, or never created by it)");
        return nullptr;
    }
    if (object->publicReferenceCount() == 0) {
        state_.report(object, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_OPERATION,
                      std::string(call) + ": " + object->label() +
                          " was released by the application (it holds no reference to it any more)");
        return nullptr;
    }
    return object;
}

Array* Device::arrayFrom(ANARIArray handle, const char* call) {
    Object* object = objectFrom(handle, call);
    if (object && !isArrayType(object->type())) {
        state_.report(object, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                      std::string(call) + ": " + object->label() + " is not an array");
        return nullptr;
    }
    return static_cast<Array*>(object);
}

// --- creation ------------------------------------------------------------------------------------------

ANARIArray Device::newArray(ANARIDataType arrayType, const void* appMemory, ANARIMemoryDeleter deleter,
                            const void* userData, ANARIDataType elementType, uint64_t n1, uint64_t n2,
                            uint64_t n3) {
    return guarded("anariNewArray", [&]() -> ANARIArray {
        if (ripple_anari::sizeOf(elementType) == 0 || elementType == ANARI_STRING) {
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                          "anariNewArray: unsupported element type " + std::string(ripple_anari::typeName(elementType)) +
                              " (" + std::to_string(elementType) + ")");
            return nullptr;
        }
        if (n1 == 0 || n2 == 0 || n3 == 0) {
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                          "anariNewArray: zero elements along an axis");
            return nullptr;
        }
        if (auto problem = Array::sizeProblem(elementType, n1, n2, n3, appMemory == nullptr)) {
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_OUT_OF_MEMORY, "anariNewArray: " + *problem);
            return nullptr;
        }
        return handleOf<ANARIArray>(
            new Array(state_, arrayType, appMemory, deleter, userData, elementType, n1, n2, n3));
    });
}

ANARIArray1D Device::newArray1D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                ANARIDataType dataType, uint64_t n1) {
    return reinterpret_cast<ANARIArray1D>(newArray(ANARI_ARRAY1D, appMemory, deleter, userData, dataType, n1, 1, 1));
}

ANARIArray2D Device::newArray2D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                ANARIDataType dataType, uint64_t n1, uint64_t n2) {
    return reinterpret_cast<ANARIArray2D>(newArray(ANARI_ARRAY2D, appMemory, deleter, userData, dataType, n1, n2, 1));
}

ANARIArray3D Device::newArray3D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                                ANARIDataType dataType, uint64_t n1, uint64_t n2, uint64_t n3) {
    return reinterpret_cast<ANARIArray3D>(newArray(ANARI_ARRAY3D, appMemory, deleter, userData, dataType, n1, n2, n3));
}

ANARIObject Device::create(ANARIDataType type, const char* subtype, const char* call) {
    return guarded(call, [&]() -> ANARIObject {
        return handleOf<ANARIObject>(createObject(state_, type, subtype ? subtype : ""));
    });
}

ANARIGeometry Device::newGeometry(const char* t) { return reinterpret_cast<ANARIGeometry>(create(ANARI_GEOMETRY, t, "anariNewGeometry")); }
ANARIMaterial Device::newMaterial(const char* t) { return reinterpret_cast<ANARIMaterial>(create(ANARI_MATERIAL, t, "anariNewMaterial")); }
ANARISampler Device::newSampler(const char* t) { return reinterpret_cast<ANARISampler>(create(ANARI_SAMPLER, t, "anariNewSampler")); }
ANARISurface Device::newSurface() { return reinterpret_cast<ANARISurface>(create(ANARI_SURFACE, "", "anariNewSurface")); }
ANARISpatialField Device::newSpatialField(const char* t) { return reinterpret_cast<ANARISpatialField>(create(ANARI_SPATIAL_FIELD, t, "anariNewSpatialField")); }
ANARIVolume Device::newVolume(const char* t) { return reinterpret_cast<ANARIVolume>(create(ANARI_VOLUME, t, "anariNewVolume")); }
ANARILight Device::newLight(const char* t) { return reinterpret_cast<ANARILight>(create(ANARI_LIGHT, t, "anariNewLight")); }
ANARIGroup Device::newGroup() { return reinterpret_cast<ANARIGroup>(create(ANARI_GROUP, "", "anariNewGroup")); }
ANARIInstance Device::newInstance(const char* t) { return reinterpret_cast<ANARIInstance>(create(ANARI_INSTANCE, t, "anariNewInstance")); }
ANARIWorld Device::newWorld() { return reinterpret_cast<ANARIWorld>(create(ANARI_WORLD, "", "anariNewWorld")); }
ANARICamera Device::newCamera(const char* t) { return reinterpret_cast<ANARICamera>(create(ANARI_CAMERA, t, "anariNewCamera")); }
ANARIRenderer Device::newRenderer(const char* t) { return reinterpret_cast<ANARIRenderer>(create(ANARI_RENDERER, t, "anariNewRenderer")); }
ANARIFrame Device::newFrame() { return reinterpret_cast<ANARIFrame>(create(ANARI_FRAME, "", "anariNewFrame")); }

ANARIObject Device::newObject(const char* objectType, const char* type) {
    static const std::pair<const char*, ANARIDataType> kTypes[] = {
        {"camera", ANARI_CAMERA},     {"frame", ANARI_FRAME},       {"geometry", ANARI_GEOMETRY},
        {"group", ANARI_GROUP},       {"instance", ANARI_INSTANCE}, {"light", ANARI_LIGHT},
        {"material", ANARI_MATERIAL}, {"renderer", ANARI_RENDERER}, {"sampler", ANARI_SAMPLER},
        {"spatialField", ANARI_SPATIAL_FIELD}, {"surface", ANARI_SURFACE}, {"volume", ANARI_VOLUME},
        {"world", ANARI_WORLD}};
    for (const auto& [name, dataType] : kTypes)
        if (objectType && std::strcmp(objectType, name) == 0) return create(dataType, type, "anariNewObject");
    state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                  std::string("anariNewObject: unknown object type '") + (objectType ? objectType : "NULL") + "'");
    return nullptr;
}

// --- parameters ----------------------------------------------------------------------------------------

void Device::setDeviceParameter(const char* name, ANARIDataType type, const void* mem) {
    const std::string key = name;
    if (key == "statusCallback" && type == ANARI_STATUS_CALLBACK) {
        std::memcpy(&pendingCallback_, mem, sizeof(pendingCallback_));
        callbackSet_ = true;
    } else if (key == "statusCallbackUserData" && type == ANARI_VOID_POINTER) {
        pendingCallbackUserPtr_ = mem;  // an ANARI_VOID_POINTER's value is `mem` itself
        callbackSet_ = true;
    } else if (key == "mpiCommunicator" && type == ANARI_VOID_POINTER) {
        state_.setCommunicatorHandle(mem);  // the address of the application's MPI_Comm
    } else if (key == "traversal" && type == ANARI_STRING) {
        const char* value = static_cast<const char*>(mem);
        if (const auto traversal = core::parseTraversal(value)) state_.setTraversal(*traversal);
        else
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                          std::string("device parameter 'traversal' is '") + value + "'; use one of " +
                              core::kTraversalNames + " (kept: " + core::traversalName(state_.traversal()) + ")");
    } else if (key == "rayExchange" && type == ANARI_STRING) {
        const char* value = static_cast<const char*>(mem);
        if (const auto kind = core::parseExchangeKind(value)) state_.setRayExchange(*kind);
        else
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                          std::string("device parameter 'rayExchange' is '") + value + "'; use one of " +
                              core::kExchangeNames + " (kept: " + core::exchangeKindName(state_.rayExchange()) + ")");
    } else if (key == "discreteMemory" && type == ANARI_BOOL) {
        int32_t on = 0;  // ANARI_BOOL is 32 bits
        std::memcpy(&on, mem, sizeof(on));
        if (!state_.setDiscreteMemory(on != 0))
            state_.report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_OPERATION,
                          "device parameter 'discreteMemory' set after the first render created the device's Vulkan "
                          "context; ignored");
    } else if (key == "vulkanDevice" && type == ANARI_STRING) {
        if (!state_.setVulkanDevice(static_cast<const char*>(mem)))
            state_.report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_OPERATION,
                          "device parameter 'vulkanDevice' set after the first render created the device's Vulkan "
                          "context; ignored");
    } else if (key == "pointer_to_mpi_communicator" && type == ANARI_UINT64) {
        const void* communicator = nullptr;  // the same address, as a number
        std::memcpy(&communicator, mem, sizeof(communicator));
        state_.setCommunicatorHandle(communicator);
    } else {
        state_.report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_ARGUMENT,
                      "device parameter '" + key + "' of type " + ripple_anari::typeName(type) +
                          " is not used by Ripple; ignored");
    }
}

void Device::setParameter(ANARIObject object, const char* name, ANARIDataType dataType, const void* mem) {
    guarded("anariSetParameter", [&] {
        // An ANARI_VOID_POINTER's value is `mem` itself, and NULL is a value like any other.
        if (!name || (!mem && dataType != ANARI_VOID_POINTER)) {
            state_.report(nullptr, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                          "anariSetParameter: NULL name or value");
            return;
        }
        if (isDevice(object)) return setDeviceParameter(name, dataType, mem);
        if (Object* target = objectFrom(object, "anariSetParameter")) target->setParameter(name, dataType, mem);
    });
}

void Device::unsetParameter(ANARIObject object, const char* name) {
    guarded("anariUnsetParameter", [&] {
        if (isDevice(object) || !name) return;
        if (Object* target = objectFrom(object, "anariUnsetParameter")) target->unsetParameter(name);
    });
}

void Device::unsetAllParameters(ANARIObject object) {
    guarded("anariUnsetAllParameters", [&] {
        if (isDevice(object)) return;
        if (Object* target = objectFrom(object, "anariUnsetAllParameters")) target->unsetAllParameters();
    });
}

void* Device::mapParameterArray(ANARIObject object, const char* name, ANARIDataType arrayType,
                                ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3,
                                uint64_t* elementStride) {
    return guarded("anariMapParameterArray", [&]() -> void* {
        Object* target = objectFrom(object, "anariMapParameterArray");
        if (!target || !name || isDevice(object)) return nullptr;
        ANARIArray handle = newArray(arrayType, nullptr, nullptr, nullptr, elementType, n1, n2, n3);
        if (!handle) return nullptr;
        auto* array = static_cast<Array*>(state_.handles.find(handle));
        target->setParameter(name, arrayType, &handle);  // the parameter holds its own reference
        auto& slot = parameterArrays_[{target, name}];
        if (slot) slot->releasePublic();
        slot = array;  // the application's (through us), until unmapped
        if (elementStride) *elementStride = ripple_anari::sizeOf(elementType);
        return array->map();
    });
}

void* Device::mapParameterArray1D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t* s) {
    return mapParameterArray(o, n, ANARI_ARRAY1D, t, n1, 1, 1, s);
}
void* Device::mapParameterArray2D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t n2,
                                  uint64_t* s) {
    return mapParameterArray(o, n, ANARI_ARRAY2D, t, n1, n2, 1, s);
}
void* Device::mapParameterArray3D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t n2,
                                  uint64_t n3, uint64_t* s) {
    return mapParameterArray(o, n, ANARI_ARRAY3D, t, n1, n2, n3, s);
}

void Device::unmapParameterArray(ANARIObject object, const char* name) {
    guarded("anariUnmapParameterArray", [&] {
        Object* target = objectFrom(object, "anariUnmapParameterArray");
        if (!target) return;
        auto it = parameterArrays_.find({target, name ? name : ""});
        if (it == parameterArrays_.end()) {
            state_.report(nullptr, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_OPERATION,
                          std::string("anariUnmapParameterArray: parameter '") + (name ? name : "NULL") +
                              "' was not mapped");
            return;
        }
        Array* array = it->second;
        parameterArrays_.erase(it);
        array->unmap();
        array->releasePublic();  // the reference anariMapParameterArray held for the application
    });
}

void Device::commitParameters(ANARIObject object) {
    guarded("anariCommitParameters", [&] {
        if (isDevice(object)) {
            if (callbackSet_) state_.setStatusCallback(pendingCallback_, pendingCallbackUserPtr_);
            return;
        }
        if (Object* target = objectFrom(object, "anariCommitParameters")) target->commitParameters();
    });
}

// --- lifetime ------------------------------------------------------------------------------------------

void Device::release(ANARIObject object) {
    if (!object) return;  // anariRelease(device, NULL) is legal and does nothing
    if (isDevice(object)) {
        if (--references_ == 0) delete this;
        return;
    }
    guarded("anariRelease", [&] {
        Object* target = state_.handles.find(object);
        if (!target) {
            objectFrom(object, "anariRelease");  // reports the stale handle
            return;
        }
        if (!target->releasePublic())
            state_.report(target, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_OPERATION,
                          "anariRelease: " + target->label() +
                              " released more often than created and retained by the application; ignored");
    });
}

void Device::retain(ANARIObject object) {
    if (!object) return;
    if (isDevice(object)) {
        ++references_;
        return;
    }
    guarded("anariRetain", [&] {
        if (Object* target = objectFrom(object, "anariRetain")) target->retainPublic();
    });
}

// --- arrays --------------------------------------------------------------------------------------------

void* Device::mapArray(ANARIArray array) {
    return guarded("anariMapArray", [&]() -> void* {
        Array* target = arrayFrom(array, "anariMapArray");
        return target ? target->map() : nullptr;
    });
}

void Device::unmapArray(ANARIArray array) {
    guarded("anariUnmapArray", [&] {
        if (Array* target = arrayFrom(array, "anariUnmapArray")) target->unmap();
    });
}

// --- properties and introspection ----------------------------------------------------------------------

int Device::getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,
                        ANARIWaitMask mask) {
    return guarded("anariGetProperty", [&]() -> int {
        if (!name || !mem) return 0;
        const std::string key = name;
        if (isDevice(object)) {
            if (key == "version" && type == ANARI_INT32 && size >= sizeof(int32_t)) {
                std::memcpy(mem, &kDeviceVersion, sizeof(int32_t));
                return 1;
            }
            // KHR_DEVICE_SYNCHRONIZATION: "waitIdle" returns once every frame in flight has finished.
            if (key == "waitIdle" && type == ANARI_BOOL && size >= sizeof(int32_t)) {
                if (mask == ANARI_WAIT) state_.waitForWork();
                const int32_t idle = mask == ANARI_WAIT || state_.idle() ? 1 : 0;
                std::memcpy(mem, &idle, sizeof(idle));
                return 1;
            }
            // Whether the device's buffers are staged as on a discrete GPU (device parameter discreteMemory or
            // RIPPLE_VK_DISCRETE_MEMORY); known once the first render has created the Vulkan context.
            if (key == "ripple.discreteMemory" && type == ANARI_BOOL && size >= sizeof(int32_t)) {
                const vk::Context* context = state_.vulkanIfCreated();
                if (!context) return 0;
                const int32_t on = context->discreteMemoryMode() ? 1 : 0;
                std::memcpy(mem, &on, sizeof(on));
                return 1;
            }
            // The Vulkan devices this process sees and the one it renders with (ripple-render --list-devices);
            // collective under MPI the first time (DeviceState::vulkanDevicesText).
            if (key == "ripple.vulkanDevices" && type == ANARI_STRING && size >= sizeof(const char*)) {
                const char* text = state_.vulkanDevicesText();
                std::memcpy(mem, &text, sizeof(text));
                return 1;
            }
            if (key == "extension" && type == ANARI_STRING_LIST && size >= sizeof(const char**)) {
                const char** list = deviceExtensions();
                std::memcpy(mem, &list, sizeof(list));
                return 1;
            }
            return 0;
        }
        Object* target = objectFrom(object, "anariGetProperty");
        return target && target->getProperty(key, type, mem, size, mask == ANARI_WAIT) ? 1 : 0;
    });
}

const char** Device::getObjectSubtypes(ANARIDataType objectType) {
    return guarded("anariGetObjectSubtypes", [&] { return objectSubtypes(objectType); });
}

const void* Device::getObjectInfo(ANARIDataType objectType, const char* objectSubtype, const char* infoName,
                                  ANARIDataType infoType) {
    return guarded("anariGetObjectInfo", [&] { return objectInfo(objectType, objectSubtype, infoName, infoType); });
}

const void* Device::getParameterInfo(ANARIDataType objectType, const char* objectSubtype,
                                     const char* parameterName, ANARIDataType parameterType, const char* infoName,
                                     ANARIDataType infoType) {
    return guarded("anariGetParameterInfo", [&] {
        return parameterInfo(objectType, objectSubtype, parameterName, parameterType, infoName, infoType);
    });
}

// --- frames --------------------------------------------------------------------------------------------

Frame* Device::frameFrom(ANARIFrame handle, const char* call) {
    Object* object = objectFrom(handle, call);
    if (object && object->type() != ANARI_FRAME) {
        state_.report(object, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                      std::string(call) + ": " + object->label() + " is not a frame");
        return nullptr;
    }
    return static_cast<Frame*>(object);
}

const void* Device::mapFrame(ANARIFrame frame, const char* channel, uint32_t* width, uint32_t* height,
                             ANARIDataType* pixelType) {
    return guarded("anariMapFrame", [&]() -> const void* {
        if (width) *width = 0;
        if (height) *height = 0;
        if (pixelType) *pixelType = ANARI_UNKNOWN;
        Frame* target = frameFrom(frame, "anariMapFrame");
        if (!target) return nullptr;
        if (!channel) {
            state_.report(target, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT, "anariMapFrame: NULL channel");
            return nullptr;
        }
        return target->map(channel, width, height, pixelType);
    });
}

void Device::unmapFrame(ANARIFrame frame, const char* channel) {
    guarded("anariUnmapFrame", [&] {
        if (Frame* target = frameFrom(frame, "anariUnmapFrame"); target && channel) target->unmap(channel);
    });
}

void Device::renderFrame(ANARIFrame frame) {
    guarded("anariRenderFrame", [&] {
        if (Frame* target = frameFrom(frame, "anariRenderFrame")) target->renderFrame();
    });
}

int Device::frameReady(ANARIFrame frame, ANARIWaitMask mask) {
    return guarded("anariFrameReady", [&]() -> int {
        Frame* target = frameFrom(frame, "anariFrameReady");
        return target && target->ready(mask == ANARI_WAIT) ? 1 : 0;
    });
}

void Device::discardFrame(ANARIFrame frame) {
    guarded("anariDiscardFrame", [&] {
        if (Frame* target = frameFrom(frame, "anariDiscardFrame")) target->discard();
    });
}

Device::ProcAddress Device::getProcAddress(const char*) { return nullptr; }  // no extension entry points

}  // namespace ripple::device
