// A device library for the loader tests: its device and library objects do nothing but record which virtual
// method each call reached, with which arguments and what it returned (see CallRecord.h). Built several
// times under different names (LOADERTEST_LIBRARY_NAME); each build exports only its entry point.
#include "CallRecord.h"

#include "anari/anari.h"
#include "anari/backend/DeviceInterface.h"
#include "anari/backend/LibraryInterface.h"

#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <stdexcept>

using loadertest::asWord;
using ripple::abi::DeviceInterface;
using ripple::abi::LibraryInterface;

namespace {

loadertest::CallRecord record;
// Kept for the ELF destructor, which runs when dlclose unmaps this library.
ANARIStatusCallback applicationCallback = nullptr;
const void* applicationCallbackUserPtr = nullptr;
bool aLibraryWasDestroyed = false;

const loadertest::CallRecord* currentRecord() { return &record; }

void note(const char* method, uint64_t returned, std::initializer_list<uint64_t> arguments) {
    record.method = method;
    record.argumentCount = int(arguments.size());
    int index = 0;
    for (uint64_t argument : arguments) record.arguments[index++] = argument;
    record.returned = returned;
    ++record.callCount;
}

// Distinct, recognisable handle values; never dereferenced.
template <class Handle>
Handle tagged(uint64_t tag) {
    return reinterpret_cast<Handle>(uintptr_t(0x7000 + tag));
}

template <class Result, class... Args>
Result answer(const char* method, Result result, Args... arguments) {
    note(method, asWord(result), {asWord(arguments)...});
    return result;
}

template <class... Args>
void noteVoid(const char* method, Args... arguments) {
    note(method, 0, {asWord(arguments)...});
}

class FakeDevice final : public DeviceInterface {
public:
    FakeDevice() { ++record.liveDevices; }
    ~FakeDevice() override { --record.liveDevices; }

    ANARIArray1D newArray1D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t numElements1) override {
        return answer(__func__, tagged<ANARIArray1D>(0), appMemory, deleter, userData, dataType, numElements1);
    }
    ANARIArray2D newArray2D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t numElements1, uint64_t numElements2) override {
        return answer(__func__, tagged<ANARIArray2D>(1), appMemory, deleter, userData, dataType, numElements1,
                      numElements2);
    }
    ANARIArray3D newArray3D(const void* appMemory, ANARIMemoryDeleter deleter, const void* userData,
                            ANARIDataType dataType, uint64_t numElements1, uint64_t numElements2,
                            uint64_t numElements3) override {
        return answer(__func__, tagged<ANARIArray3D>(2), appMemory, deleter, userData, dataType, numElements1,
                      numElements2, numElements3);
    }
    ANARIGeometry newGeometry(const char* type) override { return answer(__func__, tagged<ANARIGeometry>(3), type); }
    ANARIMaterial newMaterial(const char* type) override { return answer(__func__, tagged<ANARIMaterial>(4), type); }
    ANARISampler newSampler(const char* type) override { return answer(__func__, tagged<ANARISampler>(5), type); }
    ANARISurface newSurface() override { return answer(__func__, tagged<ANARISurface>(6)); }
    ANARISpatialField newSpatialField(const char* type) override {
        return answer(__func__, tagged<ANARISpatialField>(7), type);
    }
    ANARIVolume newVolume(const char* type) override { return answer(__func__, tagged<ANARIVolume>(8), type); }
    ANARILight newLight(const char* type) override { return answer(__func__, tagged<ANARILight>(9), type); }
    ANARIGroup newGroup() override { return answer(__func__, tagged<ANARIGroup>(10)); }
    ANARIInstance newInstance(const char* type) override { return answer(__func__, tagged<ANARIInstance>(11), type); }
    ANARIWorld newWorld() override { return answer(__func__, tagged<ANARIWorld>(12)); }
    ANARICamera newCamera(const char* type) override { return answer(__func__, tagged<ANARICamera>(13), type); }
    ANARIRenderer newRenderer(const char* type) override { return answer(__func__, tagged<ANARIRenderer>(14), type); }
    ANARIFrame newFrame() override { return answer(__func__, tagged<ANARIFrame>(15)); }

    void setParameter(ANARIObject object, const char* name, ANARIDataType dataType, const void* mem) override {
        noteVoid(__func__, object, name, dataType, mem);
    }
    void unsetParameter(ANARIObject object, const char* name) override { noteVoid(__func__, object, name); }
    void unsetAllParameters(ANARIObject object) override { noteVoid(__func__, object); }
    void* mapParameterArray1D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t numElements1,
                              uint64_t* elementStride) override {
        return answer(__func__, tagged<void*>(19), object, name, dataType, numElements1, elementStride);
    }
    void* mapParameterArray2D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t numElements1,
                              uint64_t numElements2, uint64_t* elementStride) override {
        return answer(__func__, tagged<void*>(20), object, name, dataType, numElements1, numElements2,
                      elementStride);
    }
    void* mapParameterArray3D(ANARIObject object, const char* name, ANARIDataType dataType, uint64_t numElements1,
                              uint64_t numElements2, uint64_t numElements3, uint64_t* elementStride) override {
        return answer(__func__, tagged<void*>(21), object, name, dataType, numElements1, numElements2,
                      numElements3, elementStride);
    }
    void unmapParameterArray(ANARIObject object, const char* name) override { noteVoid(__func__, object, name); }
    void commitParameters(ANARIObject object) override { noteVoid(__func__, object); }
    // Releasing the device itself deletes it, as a real device does when its last reference goes.
    void release(ANARIObject object) override {
        noteVoid(__func__, object);
        if (object == ripple::abi::handleFromDevice(this)) delete this;
    }
    void retain(ANARIObject object) override { noteVoid(__func__, object); }

    void* mapArray(ANARIArray array) override { return answer(__func__, tagged<void*>(26), array); }
    void unmapArray(ANARIArray array) override { noteVoid(__func__, array); }
    int getProperty(ANARIObject object, const char* name, ANARIDataType type, void* mem, uint64_t size,
                    ANARIWaitMask mask) override {
        return answer(__func__, 28, object, name, type, mem, size, mask);
    }
    const char** getObjectSubtypes(ANARIDataType objectType) override {
        return answer(__func__, tagged<const char**>(29), objectType);
    }
    const void* getObjectInfo(ANARIDataType objectType, const char* objectSubtype, const char* infoName,
                              ANARIDataType infoType) override {
        return answer(__func__, tagged<const void*>(30), objectType, objectSubtype, infoName, infoType);
    }
    const void* getParameterInfo(ANARIDataType objectType, const char* objectSubtype, const char* parameterName,
                                 ANARIDataType parameterType, const char* infoName, ANARIDataType infoType) override {
        return answer(__func__, tagged<const void*>(31), objectType, objectSubtype, parameterName, parameterType,
                      infoName, infoType);
    }

    const void* mapFrame(ANARIFrame frame, const char* channel, uint32_t* width, uint32_t* height,
                         ANARIDataType* pixelType) override {
        return answer(__func__, tagged<const void*>(32), frame, channel, width, height, pixelType);
    }
    void unmapFrame(ANARIFrame frame, const char* channel) override { noteVoid(__func__, frame, channel); }
    void renderFrame(ANARIFrame frame) override { noteVoid(__func__, frame); }
    int frameReady(ANARIFrame frame, ANARIWaitMask mask) override {
        if (mask == loadertest::throwingWaitMask) throw std::runtime_error("frameReady was told to throw");
        return answer(__func__, 35, frame, mask);
    }
    void discardFrame(ANARIFrame frame) override { noteVoid(__func__, frame); }

    ANARIObject newObject(const char* objectType, const char* type) override {
        return answer(__func__, tagged<ANARIObject>(37), objectType, type);
    }
    ProcAddress getProcAddress(const char* name) override {
        const bool wantsRecord = name != nullptr && std::strcmp(name, loadertest::callRecordProcName) == 0;
        return answer(__func__, wantsRecord ? reinterpret_cast<ProcAddress>(&currentRecord) : ProcAddress{nullptr},
                      name);
    }
};

class FakeLibrary final : public LibraryInterface {
public:
    FakeLibrary(void* dlopenHandleIn, ANARIStatusCallback callback, const void* callbackUserPtr)
        : LibraryInterface(dlopenHandleIn, callback, callbackUserPtr) {
        ++record.liveLibraries;
    }
    ~FakeLibrary() override {
        --record.liveLibraries;
        aLibraryWasDestroyed = true;
        if (defaultStatusCallback != nullptr)
            defaultStatusCallback(defaultStatusCallbackUserPtr, nullptr, nullptr, ANARI_LIBRARY, ANARI_SEVERITY_INFO,
                                  ANARI_STATUS_NO_ERROR, loadertest::libraryDestroyedMessage);
    }

    ANARIDevice newDevice(const char* subtype) override {
        return answer(__func__, ripple::abi::handleFromDevice(new FakeDevice), subtype);
    }
    ANARIDevice newInitializedDevice(const char* subtype, ANARIParameterValue* initializers) override {
        return answer(__func__, ripple::abi::handleFromDevice(new FakeDevice), subtype, initializers);
    }
    const char** getDeviceExtensions(const char* deviceSubtype) override {
        static const char* extensions[] = {"ANARI_KHR_GEOMETRY_TRIANGLE", nullptr};
        return answer(__func__, extensions, deviceSubtype);
    }
    const char** getDeviceSubtypes() override {
        static const char* subtypes[] = {"default", nullptr};
        return answer(__func__, subtypes);
    }
    void loadModule(const char* name) override { noteVoid(__func__, name); }
    void unloadModule(const char* name) override { noteVoid(__func__, name); }
};

// Runs when dlclose unmaps the library: after the library object's destructor if the loader keeps the order.
__attribute__((destructor)) void reportModuleUnmapped() {
    if (applicationCallback != nullptr && aLibraryWasDestroyed && record.liveLibraries == 0)
        applicationCallback(applicationCallbackUserPtr, nullptr, nullptr, ANARI_LIBRARY, ANARI_SEVERITY_INFO,
                            ANARI_STATUS_NO_ERROR, loadertest::moduleUnmappedMessage);
}

}  // namespace

#define LOADERTEST_PASTE(prefix, name, suffix) prefix##name##suffix
#define LOADERTEST_ENTRY_POINT(name) LOADERTEST_PASTE(anari_library_, name, _new_library)

extern "C" __attribute__((visibility("default"))) ANARILibrary LOADERTEST_ENTRY_POINT(LOADERTEST_LIBRARY_NAME)(
    void* dlopenHandle, ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr) {
    const char* failure = std::getenv(loadertest::newLibraryFailureVariable);
    if (failure != nullptr && std::strcmp(failure, "null") == 0) return nullptr;
    if (failure != nullptr && std::strcmp(failure, "throw") == 0)
        throw std::runtime_error("the entry point was told to throw");
    applicationCallback = defaultCallback;
    applicationCallbackUserPtr = defaultCallbackUserPtr;
    return ripple::abi::handleFromLibrary(new FakeLibrary(dlopenHandle, defaultCallback, defaultCallbackUserPtr));
}
