// PtcDevice (see PtcDevice.h): object handles are the wrapped device's own, so most calls pass straight
// through; frames keep a little state on this side for the compositing.
#include "anari/ptc/PtcDevice.h"

#include "anari/anari_type_traits.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>

namespace ripple::ptc {

namespace {

uint8_t toUnorm8(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }
float linearToSrgb(float value) {
    value = std::clamp(value, 0.0f, 1.0f);
    return value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

PtcDevice::PtcDevice(ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr)
    : callback_(defaultCallback), callbackUserPtr_(defaultCallbackUserPtr) {
    libraryName_ = defaultWrappedLibraryName();
}

PtcDevice::~PtcDevice() {
    if (wrapped_) wrapped_->release(wrappedHandle());
    unloadWrappedLibrary(library_);
}

void PtcDevice::report(ANARIStatusSeverity severity, const std::string& message) const {
    if (callback_)
        callback_(callbackUserPtr_, handleFromDevice(const_cast<PtcDevice*>(this)), handleFromDevice(const_cast<PtcDevice*>(this)),
                  ANARI_DEVICE, severity, severity == ANARI_SEVERITY_ERROR ? ANARI_STATUS_INVALID_OPERATION : ANARI_STATUS_NO_ERROR,
                  ("ripple_ptc: " + message).c_str());
}

void PtcDevice::loadWrapped() {
    library_ = loadWrappedLibrary(libraryName_, callback_, callbackUserPtr_);  // reports to the application
    ANARIDevice device = library_.library->newDevice("default");
    if (!device) throw std::runtime_error("the wrapped library '" + libraryName_ + "' created no device");
    wrapped_ = abi::deviceFromHandle(device);
    // The wrapped device renders this rank's share alone: a data-parallel device must not talk to the
    // other ranks itself, or they would be composited twice.
    if (const void* self = mpi::Communicator::selfHandle())
        wrapped_->setParameter(device, "mpiCommunicator", ANARI_VOID_POINTER, self);
    for (const PendingParameter& p : pending_) {
        const void* mem = p.bytes.data();
        if (p.type == ANARI_STRING) mem = p.text.c_str();
        if (p.type == ANARI_VOID_POINTER) std::memcpy(&mem, p.bytes.data(), sizeof(mem));
        wrapped_->setParameter(device, p.name.c_str(), p.type, mem);
    }
    pending_.clear();
}

abi::DeviceInterface* PtcDevice::wrapped() {
    if (wrapped_ || loadFailed_) return wrapped_;
    try {
        loadWrapped();
    } catch (const std::exception& error) {
        loadFailed_ = true;
        report(ANARI_SEVERITY_ERROR, error.what());
    }
    return wrapped_;
}

// --- object creation: straight through -----------------------------------------------------------------

#define RIPPLE_PTC_FORWARD(fallback, call)  \
    if (abi::DeviceInterface* device = wrapped()) return device->call; \
    return fallback

ANARIArray1D PtcDevice::newArray1D(const void* m, ANARIMemoryDeleter d, const void* u, ANARIDataType t, uint64_t n1) {
    RIPPLE_PTC_FORWARD(nullptr, newArray1D(m, d, u, t, n1));
}
ANARIArray2D PtcDevice::newArray2D(const void* m, ANARIMemoryDeleter d, const void* u, ANARIDataType t, uint64_t n1,
                                   uint64_t n2) {
    RIPPLE_PTC_FORWARD(nullptr, newArray2D(m, d, u, t, n1, n2));
}
ANARIArray3D PtcDevice::newArray3D(const void* m, ANARIMemoryDeleter d, const void* u, ANARIDataType t, uint64_t n1,
                                   uint64_t n2, uint64_t n3) {
    RIPPLE_PTC_FORWARD(nullptr, newArray3D(m, d, u, t, n1, n2, n3));
}
ANARIGeometry PtcDevice::newGeometry(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newGeometry(type)); }
ANARIMaterial PtcDevice::newMaterial(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newMaterial(type)); }
ANARISampler PtcDevice::newSampler(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newSampler(type)); }
ANARISurface PtcDevice::newSurface() { RIPPLE_PTC_FORWARD(nullptr, newSurface()); }
ANARISpatialField PtcDevice::newSpatialField(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newSpatialField(type)); }
ANARIVolume PtcDevice::newVolume(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newVolume(type)); }
ANARILight PtcDevice::newLight(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newLight(type)); }
ANARIGroup PtcDevice::newGroup() { RIPPLE_PTC_FORWARD(nullptr, newGroup()); }
ANARIInstance PtcDevice::newInstance(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newInstance(type)); }
ANARIWorld PtcDevice::newWorld() { RIPPLE_PTC_FORWARD(nullptr, newWorld()); }
ANARICamera PtcDevice::newCamera(const char* type) { RIPPLE_PTC_FORWARD(nullptr, newCamera(type)); }
ANARIRenderer PtcDevice::newRenderer(const char* type) {
    abi::DeviceInterface* device = wrapped();
    if (!device) return nullptr;
    ANARIRenderer renderer = device->newRenderer(type);
    backgroundAlpha_.erase(renderer);  // a handle may be reused: a new renderer has the default background
    return renderer;
}
ANARIObject PtcDevice::newObject(const char* objectType, const char* type) {
    RIPPLE_PTC_FORWARD(nullptr, newObject(objectType, type));
}

ANARIFrame PtcDevice::newFrame() {
    abi::DeviceInterface* device = wrapped();
    if (!device) return nullptr;
    ANARIFrame frame = device->newFrame();
    if (!frame) return nullptr;
    const ANARIDataType color = ANARI_FLOAT32_VEC4, depth = ANARI_FLOAT32;
    device->setParameter(frame, "channel.color", ANARI_DATA_TYPE, &color);
    device->setParameter(frame, "channel.depth", ANARI_DATA_TYPE, &depth);
    frames_[frame].communicatorHandle = communicatorHandle_;
    return frame;
}

// --- parameters ----------------------------------------------------------------------------------------

void PtcDevice::setDeviceParameter(const char* name, ANARIDataType dataType, const void* mem) {
    const std::string key = name;
    if (key == "library" && dataType == ANARI_STRING) {
        if (wrapped_ || loadFailed_)
            report(ANARI_SEVERITY_WARNING, "\"library\" set after the wrapped device was created: ignored");
        else
            libraryName_ = static_cast<const char*>(mem);
        return;
    }
    if (key == "compositing" && dataType == ANARI_STRING) {
        const char* value = static_cast<const char*>(mem);
        if (const auto method = mpi::parseCompositeMethod(value)) compositeMethod_ = *method;
        else
            report(ANARI_SEVERITY_ERROR, std::string("device parameter 'compositing' is '") + value + "'; use one of " +
                                             mpi::kCompositeMethodNames + " (kept: " +
                                             mpi::compositeMethodName(compositeMethod_) + ")");
        return;
    }
    if (key == "mpiCommunicator" && dataType == ANARI_VOID_POINTER) {
        communicatorHandle_ = mpi::Communicator::copyHandle(mem);  // a VOID_POINTER's value is mem itself
        return;
    }
    if (key == "pointer_to_mpi_communicator" && dataType == ANARI_UINT64) {
        const void* address = nullptr;  // the address of the application's MPI_Comm, as a number
        std::memcpy(&address, mem, sizeof(address));
        communicatorHandle_ = mpi::Communicator::copyHandle(address);
        return;
    }
    if (key == "statusCallback" && dataType == ANARI_STATUS_CALLBACK)
        std::memcpy(&callback_, mem, sizeof(callback_));
    if (key == "statusCallbackUserData" && dataType == ANARI_VOID_POINTER) callbackUserPtr_ = mem;
    if (wrapped_) return wrapped_->setParameter(wrappedHandle(), name, dataType, mem);
    PendingParameter p{key, dataType, {}, {}};
    if (dataType == ANARI_STRING) {
        p.text = static_cast<const char*>(mem);  // ANARI passes the characters themselves
    } else if (dataType == ANARI_VOID_POINTER) {
        const auto* value = reinterpret_cast<const uint8_t*>(&mem);  // the pointer is the value
        p.bytes.assign(value, value + sizeof(mem));
    } else {
        const size_t bytes = ripple_anari::sizeOf(dataType);
        p.bytes.assign(static_cast<const uint8_t*>(mem), static_cast<const uint8_t*>(mem) + bytes);
    }
    pending_.push_back(std::move(p));
}

void PtcDevice::setFrameParameter(FrameState& frame, ANARIFrame handle, const char* name, ANARIDataType dataType,
                                  const void* mem) {
    const std::string key = name;
    if (key == "channel.color" && dataType == ANARI_DATA_TYPE) {
        std::memcpy(&frame.colorType, mem, sizeof(ANARIDataType));
        return;  // the wrapped frame keeps FLOAT32_VEC4
    }
    if (key == "channel.depth" && dataType == ANARI_DATA_TYPE) {
        std::memcpy(&frame.depthType, mem, sizeof(ANARIDataType));
        return;
    }
    if (key == "mpiCommunicator" && dataType == ANARI_VOID_POINTER) {
        frame.communicatorHandle = mpi::Communicator::copyHandle(mem);
        return;
    }
    if (key == "renderer" && dataType == ANARI_RENDERER) std::memcpy(&frame.renderer, mem, sizeof(frame.renderer));
    if (key == "size" && dataType == ANARI_UINT32_VEC2) {
        uint32_t size[2];
        std::memcpy(size, mem, sizeof(size));
        frame.width = size[0];
        frame.height = size[1];
    }
    wrapped_->setParameter(handle, name, dataType, mem);
}

void PtcDevice::setParameter(ANARIObject object, const char* name, ANARIDataType dataType, const void* mem) {
    // An ANARI_VOID_POINTER's value is `mem` itself, and NULL is a value like any other.
    if (!name || (!mem && dataType != ANARI_VOID_POINTER))
        return report(ANARI_SEVERITY_ERROR, "anariSetParameter: NULL name or value");
    if (isDevice(object)) return setDeviceParameter(name, dataType, mem);
    if (!wrapped()) return;
    if (auto it = frames_.find(reinterpret_cast<ANARIFrame>(object)); it != frames_.end())
        return setFrameParameter(it->second, it->first, name, dataType, mem);
    if (std::strcmp(name, "background") == 0) {
        float rgba[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        if (dataType == ANARI_FLOAT32_VEC4) std::memcpy(rgba, mem, sizeof(rgba));
        backgroundAlpha_[object] = rgba[3];
    }
    wrapped_->setParameter(object, name, dataType, mem);
}

void PtcDevice::unsetParameter(ANARIObject object, const char* name) {
    if (isDevice(object)) {
        if (wrapped_) wrapped_->unsetParameter(wrappedHandle(), name);
        return;
    }
    if (name && std::strcmp(name, "background") == 0) backgroundAlpha_.erase(object);
    RIPPLE_PTC_FORWARD(void(), unsetParameter(object, name));
}
void PtcDevice::unsetAllParameters(ANARIObject object) {
    if (isDevice(object)) {
        if (wrapped_) wrapped_->unsetAllParameters(wrappedHandle());
        return;
    }
    backgroundAlpha_.erase(object);
    RIPPLE_PTC_FORWARD(void(), unsetAllParameters(object));
}
void* PtcDevice::mapParameterArray1D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t* s) {
    RIPPLE_PTC_FORWARD(nullptr, mapParameterArray1D(o, n, t, n1, s));
}
void* PtcDevice::mapParameterArray2D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t n2,
                                     uint64_t* s) {
    RIPPLE_PTC_FORWARD(nullptr, mapParameterArray2D(o, n, t, n1, n2, s));
}
void* PtcDevice::mapParameterArray3D(ANARIObject o, const char* n, ANARIDataType t, uint64_t n1, uint64_t n2,
                                     uint64_t n3, uint64_t* s) {
    RIPPLE_PTC_FORWARD(nullptr, mapParameterArray3D(o, n, t, n1, n2, n3, s));
}
void PtcDevice::unmapParameterArray(ANARIObject object, const char* name) {
    RIPPLE_PTC_FORWARD(void(), unmapParameterArray(object, name));
}

void PtcDevice::commitParameters(ANARIObject object) {
    if (isDevice(object)) {
        if (abi::DeviceInterface* device = wrapped()) device->commitParameters(wrappedHandle());
        return;
    }
    abi::DeviceInterface* device = wrapped();
    if (!device) return;
    device->commitParameters(object);
    auto it = frames_.find(reinterpret_cast<ANARIFrame>(object));
    if (it == frames_.end()) return;
    FrameState& frame = it->second;
    try {
        if (!frame.compositor || frame.compositeMethod != compositeMethod_) {  // collective: every rank commits
            frame.compositor.reset();
            frame.compositor = std::make_unique<mpi::Compositor>(mpi::Communicator::fromHandle(frame.communicatorHandle.get()),
                                                                 compositeMethod_);
            frame.compositeMethod = compositeMethod_;
        }
        frame.compositor->resize(frame.width, frame.height);
    } catch (const std::exception& error) {
        report(ANARI_SEVERITY_ERROR, std::string("anariCommitParameters(frame): ") + error.what());
    }
}

// --- lifetime ------------------------------------------------------------------------------------------

void PtcDevice::release(ANARIObject object) {
    if (!object) return;
    if (isDevice(object)) {
        if (--references_ == 0) delete this;
        return;
    }
    if (!wrapped_) return;
    wrapped_->release(object);
    auto it = frames_.find(reinterpret_cast<ANARIFrame>(object));
    if (it != frames_.end() && --it->second.references == 0) frames_.erase(it);
}

void PtcDevice::retain(ANARIObject object) {
    if (!object) return;
    if (isDevice(object)) {
        ++references_;
        return;
    }
    if (!wrapped_) return;
    wrapped_->retain(object);
    if (auto it = frames_.find(reinterpret_cast<ANARIFrame>(object)); it != frames_.end()) ++it->second.references;
}

void* PtcDevice::mapArray(ANARIArray array) { RIPPLE_PTC_FORWARD(nullptr, mapArray(array)); }
void PtcDevice::unmapArray(ANARIArray array) { RIPPLE_PTC_FORWARD(void(), unmapArray(array)); }

// --- queries -------------------------------------------------------------------------------------------

int PtcDevice::getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,
                           ANARIWaitMask mask) {
    if (isDevice(object)) {
        abi::DeviceInterface* device = wrapped();
        if (!device) return 0;
        if (name && std::strcmp(name, "extension") == 0 && type == ANARI_STRING_LIST && mem &&
            size >= sizeof(const char**)) {
            const char** wrappedList = nullptr;
            if (!device->getProperty(wrappedHandle(), name, type, &wrappedList, sizeof(wrappedList), mask))
                wrappedList = nullptr;
            const char** list = compositedExtensions(wrappedList);
            std::memcpy(mem, &list, sizeof(list));
            return 1;
        }
        return device->getProperty(wrappedHandle(), name, type, mem, size, mask);
    }
    // A frame's "ripple.compositing" (STRING): the method its compositor was made with, answered here.
    if (name && std::strcmp(name, "ripple.compositing") == 0 && type == ANARI_STRING && mem &&
        size >= sizeof(const char*)) {
        const auto it = frames_.find(reinterpret_cast<ANARIFrame>(object));
        if (it == frames_.end() || !it->second.compositor) return 0;
        const char* method = mpi::compositeMethodName(it->second.compositeMethod);
        std::memcpy(mem, &method, sizeof(method));
        return 1;
    }
    RIPPLE_PTC_FORWARD(0, getProperty(object, name, type, mem, size, mask));
}
const char** PtcDevice::getObjectSubtypes(ANARIDataType objectType) {
    RIPPLE_PTC_FORWARD(nullptr, getObjectSubtypes(objectType));
}
const void* PtcDevice::getObjectInfo(ANARIDataType objectType, const char* subtype, const char* infoName,
                                     ANARIDataType infoType) {
    RIPPLE_PTC_FORWARD(nullptr, getObjectInfo(objectType, subtype, infoName, infoType));
}
const void* PtcDevice::getParameterInfo(ANARIDataType objectType, const char* subtype, const char* parameterName,
                                        ANARIDataType parameterType, const char* infoName, ANARIDataType infoType) {
    RIPPLE_PTC_FORWARD(nullptr, getParameterInfo(objectType, subtype, parameterName, parameterType, infoName, infoType));
}
PtcDevice::ProcAddress PtcDevice::getProcAddress(const char* name) { RIPPLE_PTC_FORWARD(nullptr, getProcAddress(name)); }

// --- frames --------------------------------------------------------------------------------------------

void PtcDevice::renderFrame(ANARIFrame handle) {
    auto it = frames_.find(handle);
    if (!wrapped_ || it == frames_.end()) return report(ANARI_SEVERITY_ERROR, "anariRenderFrame: not a frame of this device");
    FrameState& frame = it->second;
    if (!frame.compositor) return report(ANARI_SEVERITY_ERROR, "anariRenderFrame: the frame was never committed");
    wrapped_->renderFrame(handle);
    wrapped_->frameReady(handle, ANARI_WAIT);
    uint32_t width = 0, height = 0, depthWidth = 0, depthHeight = 0;
    ANARIDataType colorType = ANARI_UNKNOWN, depthType = ANARI_UNKNOWN;
    const auto* color = static_cast<const float*>(wrapped_->mapFrame(handle, "channel.color", &width, &height, &colorType));
    const auto* depth =
        static_cast<const float*>(wrapped_->mapFrame(handle, "channel.depth", &depthWidth, &depthHeight, &depthType));
    try {
        // Every rank goes through the collective, even with a bad local image, so none is left waiting.
        const bool usable = color && depth && colorType == ANARI_FLOAT32_VEC4 && depthType == ANARI_FLOAT32 &&
                            width == frame.width && height == frame.height && depthWidth == width &&
                            depthHeight == height;
        const size_t pixels = size_t(frame.width) * frame.height;
        std::vector<float> blankColor, blankDepth;
        auto background = backgroundAlpha_.find(frame.renderer);
        if (usable && background != backgroundAlpha_.end() && background->second == 0.0f) {
            // A transparent background gives no alpha, so alpha at infinite depth is an edge whose latest
            // sample missed: composited behind every surface of the pixel instead of dropped as background.
            blankDepth.assign(depth, depth + pixels);
            for (size_t p = 0; p < pixels; ++p)
                if (std::isinf(blankDepth[p]) && color[p * 4 + 3] > 0.0f) blankDepth[p] = std::numeric_limits<float>::max();
            depth = blankDepth.data();
        }
        if (!usable) {
            report(ANARI_SEVERITY_ERROR, "anariRenderFrame: the wrapped device gave no FLOAT32_VEC4 color and FLOAT32 "
                                         "depth of the frame's size; this rank contributes nothing");
            blankColor.assign(pixels * 4, 0.0f);
            blankDepth.assign(pixels, INFINITY);
        }
        frame.compositor->composite(usable ? std::span<const float>(color, pixels * 4) : std::span<const float>(blankColor),
                                    usable ? std::span<const float>(depth, pixels) : std::span<const float>(blankDepth));
    } catch (const std::exception& error) {
        report(ANARI_SEVERITY_ERROR, std::string("anariRenderFrame: compositing failed: ") + error.what());
    }
    if (color) wrapped_->unmapFrame(handle, "channel.color");
    if (depth) wrapped_->unmapFrame(handle, "channel.depth");
}

int PtcDevice::frameReady(ANARIFrame frame, ANARIWaitMask) {
    return frames_.count(frame) ? 1 : 0;  // renderFrame returns only once the composite is done
}

void PtcDevice::discardFrame(ANARIFrame frame) { RIPPLE_PTC_FORWARD(void(), discardFrame(frame)); }

const void* PtcDevice::mapFrame(ANARIFrame handle, const char* channel, uint32_t* width, uint32_t* height,
                                ANARIDataType* pixelType) {
    auto it = frames_.find(handle);
    if (!wrapped_ || !channel || it == frames_.end()) return nullptr;
    FrameState& frame = it->second;
    const std::string name = channel;
    if (name != "channel.color" && name != "channel.depth")
        return wrapped_->mapFrame(handle, channel, width, height, pixelType);  // this rank's own
    *width = *height = 0;
    *pixelType = ANARI_UNKNOWN;
    // Only rank 0 holds the composited image.
    if (!frame.compositor || frame.compositor->rgba().empty()) return nullptr;
    const std::vector<float>& rgba = frame.compositor->rgba();
    if (name == "channel.depth") {
        if (frame.depthType != ANARI_FLOAT32) return nullptr;
        *width = frame.width;
        *height = frame.height;
        *pixelType = ANARI_FLOAT32;
        return frame.compositor->depth().data();
    }
    *width = frame.width;
    *height = frame.height;
    *pixelType = frame.colorType;
    switch (frame.colorType) {
    case ANARI_FLOAT32_VEC4: return rgba.data();
    case ANARI_UFIXED8_VEC4:
    case ANARI_UFIXED8_RGBA_SRGB: {
        const bool srgb = frame.colorType == ANARI_UFIXED8_RGBA_SRGB;
        frame.mappedColor.resize(rgba.size());
        for (size_t i = 0; i < rgba.size(); ++i)
            frame.mappedColor[i] = toUnorm8(srgb && i % 4 != 3 ? linearToSrgb(rgba[i]) : rgba[i]);
        return frame.mappedColor.data();
    }
    default:
        *width = *height = 0;
        *pixelType = ANARI_UNKNOWN;
        report(ANARI_SEVERITY_ERROR, "anariMapFrame: channel.color type " + std::to_string(int(frame.colorType)) +
                                         " is not one ripple_ptc converts to (FLOAT32_VEC4, UFIXED8_VEC4, "
                                         "UFIXED8_RGBA_SRGB)");
        return nullptr;
    }
}

void PtcDevice::unmapFrame(ANARIFrame frame, const char* channel) {
    if (!channel || !wrapped_) return;
    const std::string name = channel;
    if (name != "channel.color" && name != "channel.depth") wrapped_->unmapFrame(frame, channel);
}

}  // namespace ripple::ptc
