// The layout contract of ripple::abi::DeviceInterface and LibraryInterface (ANARI.md section 3), read from
// what the compiler produced: virtual slot numbers, destructor slots and the dlopen handle's offset.
#include "anari/backend/DeviceInterface.h"
#include "anari/backend/LibraryInterface.h"

#include <doctest/doctest.h>

#include <cstring>
#include <new>

using ripple::abi::DeviceInterface;
using ripple::abi::LibraryInterface;

namespace {

// Under the Itanium C++ ABI a pointer to a virtual member function holds its byte offset in the vtable,
// marked by a low bit: plus one in the pointer word on x86-64, in the adjustment word on ARM.
template <class MemberFunction>
long vtableSlot(MemberFunction memberFunction) {
    struct Representation {
        uintptr_t pointer;
        ptrdiff_t adjustment;
    };
    static_assert(sizeof(MemberFunction) == sizeof(Representation));
    Representation words;
    std::memcpy(&words, &memberFunction, sizeof words);
#if defined(__aarch64__) || defined(__arm__)
    if ((words.adjustment & 1) == 0) return -1;
    return long(words.pointer / sizeof(void*));
#else
    if ((words.pointer & 1) == 0) return -1;  // not virtual
    return long((words.pointer - 1) / sizeof(void*));
#endif
}

using DestructorEntry = void (*)(void* object);

DestructorEntry vtableEntry(const void* object, int slot) {
    void* const* vtable = *static_cast<void* const* const*>(object);
    return reinterpret_cast<DestructorEntry>(vtable[slot]);
}

int destructorRuns = 0;
int deallocations = 0;

// Implements nothing but the destructor, and counts what the two destructor slots do.
struct ProbeDevice final : DeviceInterface {
    ~ProbeDevice() override { ++destructorRuns; }
    static void operator delete(void* memory) {
        ++deallocations;
        ::operator delete(memory);
    }
    ANARIArray1D newArray1D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t) override {
        return nullptr;
    }
    ANARIArray2D newArray2D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t,
                            uint64_t) override {
        return nullptr;
    }
    ANARIArray3D newArray3D(const void*, ANARIMemoryDeleter, const void*, ANARIDataType, uint64_t, uint64_t,
                            uint64_t) override {
        return nullptr;
    }
    ANARIGeometry newGeometry(const char*) override { return nullptr; }
    ANARIMaterial newMaterial(const char*) override { return nullptr; }
    ANARISampler newSampler(const char*) override { return nullptr; }
    ANARISurface newSurface() override { return nullptr; }
    ANARISpatialField newSpatialField(const char*) override { return nullptr; }
    ANARIVolume newVolume(const char*) override { return nullptr; }
    ANARILight newLight(const char*) override { return nullptr; }
    ANARIGroup newGroup() override { return nullptr; }
    ANARIInstance newInstance(const char*) override { return nullptr; }
    ANARIWorld newWorld() override { return nullptr; }
    ANARICamera newCamera(const char*) override { return nullptr; }
    ANARIRenderer newRenderer(const char*) override { return nullptr; }
    ANARIFrame newFrame() override { return nullptr; }
    void setParameter(ANARIObject, const char*, ANARIDataType, const void*) override {}
    void unsetParameter(ANARIObject, const char*) override {}
    void unsetAllParameters(ANARIObject) override {}
    void* mapParameterArray1D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t*) override {
        return nullptr;
    }
    void* mapParameterArray2D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t, uint64_t*) override {
        return nullptr;
    }
    void* mapParameterArray3D(ANARIObject, const char*, ANARIDataType, uint64_t, uint64_t, uint64_t,
                              uint64_t*) override {
        return nullptr;
    }
    void unmapParameterArray(ANARIObject, const char*) override {}
    void commitParameters(ANARIObject) override {}
    void release(ANARIObject) override {}
    void retain(ANARIObject) override {}
    void* mapArray(ANARIArray) override { return nullptr; }
    void unmapArray(ANARIArray) override {}
    int getProperty(ANARIObject, const char*, ANARIDataType, void*, uint64_t, ANARIWaitMask) override { return 0; }
    const char** getObjectSubtypes(ANARIDataType) override { return nullptr; }
    const void* getObjectInfo(ANARIDataType, const char*, const char*, ANARIDataType) override { return nullptr; }
    const void* getParameterInfo(ANARIDataType, const char*, const char*, ANARIDataType, const char*,
                                 ANARIDataType) override {
        return nullptr;
    }
    const void* mapFrame(ANARIFrame, const char*, uint32_t*, uint32_t*, ANARIDataType*) override { return nullptr; }
    void unmapFrame(ANARIFrame, const char*) override {}
    void renderFrame(ANARIFrame) override {}
    int frameReady(ANARIFrame, ANARIWaitMask) override { return 0; }
    void discardFrame(ANARIFrame) override {}
    ANARIObject newObject(const char*, const char*) override { return nullptr; }
    ProcAddress getProcAddress(const char*) override { return nullptr; }
};

struct ProbeLibrary final : LibraryInterface {
    ProbeLibrary(void* handle, ANARIStatusCallback callback, const void* userPtr)
        : LibraryInterface(handle, callback, userPtr) {}
    ~ProbeLibrary() override { ++destructorRuns; }
    static void operator delete(void* memory) {
        ++deallocations;
        ::operator delete(memory);
    }
    ANARIDevice newDevice(const char*) override { return nullptr; }
    ANARIDevice newInitializedDevice(const char*, ANARIParameterValue*) override { return nullptr; }
    const char** getDeviceExtensions(const char*) override { return nullptr; }
    const char** getDeviceSubtypes() override { return nullptr; }
    void loadModule(const char*) override {}
    void unloadModule(const char*) override {}
};

void statusCallbackForLayout(const void*, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity,
                             ANARIStatusCode, const char*) {}

}  // namespace

TEST_CASE("DeviceInterface methods sit in the vtable slots of ANARI.md section 3") {
    CHECK(vtableSlot(&DeviceInterface::newArray1D) == 0);
    CHECK(vtableSlot(&DeviceInterface::newArray2D) == 1);
    CHECK(vtableSlot(&DeviceInterface::newArray3D) == 2);
    CHECK(vtableSlot(&DeviceInterface::newGeometry) == 3);
    CHECK(vtableSlot(&DeviceInterface::newMaterial) == 4);
    CHECK(vtableSlot(&DeviceInterface::newSampler) == 5);
    CHECK(vtableSlot(&DeviceInterface::newSurface) == 6);
    CHECK(vtableSlot(&DeviceInterface::newSpatialField) == 7);
    CHECK(vtableSlot(&DeviceInterface::newVolume) == 8);
    CHECK(vtableSlot(&DeviceInterface::newLight) == 9);
    CHECK(vtableSlot(&DeviceInterface::newGroup) == 10);
    CHECK(vtableSlot(&DeviceInterface::newInstance) == 11);
    CHECK(vtableSlot(&DeviceInterface::newWorld) == 12);
    CHECK(vtableSlot(&DeviceInterface::newCamera) == 13);
    CHECK(vtableSlot(&DeviceInterface::newRenderer) == 14);
    CHECK(vtableSlot(&DeviceInterface::newFrame) == 15);
    CHECK(vtableSlot(&DeviceInterface::setParameter) == 16);
    CHECK(vtableSlot(&DeviceInterface::unsetParameter) == 17);
    CHECK(vtableSlot(&DeviceInterface::unsetAllParameters) == 18);
    CHECK(vtableSlot(&DeviceInterface::mapParameterArray1D) == 19);
    CHECK(vtableSlot(&DeviceInterface::mapParameterArray2D) == 20);
    CHECK(vtableSlot(&DeviceInterface::mapParameterArray3D) == 21);
    CHECK(vtableSlot(&DeviceInterface::unmapParameterArray) == 22);
    CHECK(vtableSlot(&DeviceInterface::commitParameters) == 23);
    CHECK(vtableSlot(&DeviceInterface::release) == 24);
    CHECK(vtableSlot(&DeviceInterface::retain) == 25);
    CHECK(vtableSlot(&DeviceInterface::mapArray) == 26);
    CHECK(vtableSlot(&DeviceInterface::unmapArray) == 27);
    CHECK(vtableSlot(&DeviceInterface::getProperty) == 28);
    CHECK(vtableSlot(&DeviceInterface::getObjectSubtypes) == 29);
    CHECK(vtableSlot(&DeviceInterface::getObjectInfo) == 30);
    CHECK(vtableSlot(&DeviceInterface::getParameterInfo) == 31);
    CHECK(vtableSlot(&DeviceInterface::mapFrame) == 32);
    CHECK(vtableSlot(&DeviceInterface::unmapFrame) == 33);
    CHECK(vtableSlot(&DeviceInterface::renderFrame) == 34);
    CHECK(vtableSlot(&DeviceInterface::frameReady) == 35);
    CHECK(vtableSlot(&DeviceInterface::discardFrame) == 36);
    CHECK(vtableSlot(&DeviceInterface::newObject) == 37);
    CHECK(vtableSlot(&DeviceInterface::getProcAddress) == 38);
}

TEST_CASE("DeviceInterface destructors are slots 39 (complete) and 40 (deleting)") {
    destructorRuns = 0;
    deallocations = 0;
    alignas(ProbeDevice) unsigned char storage[sizeof(ProbeDevice)];
    DeviceInterface* inPlace = new (storage) ProbeDevice;
    vtableEntry(inPlace, 39)(inPlace);
    CHECK(destructorRuns == 1);
    CHECK(deallocations == 0);

    DeviceInterface* onHeap = new ProbeDevice;
    vtableEntry(onHeap, 40)(onHeap);
    CHECK(destructorRuns == 2);
    CHECK(deallocations == 1);
}

TEST_CASE("LibraryInterface: destructors in slots 0-1, methods in 2-7, dlopen handle at offset 8") {
    CHECK(vtableSlot(&LibraryInterface::newDevice) == 2);
    CHECK(vtableSlot(&LibraryInterface::newInitializedDevice) == 3);
    CHECK(vtableSlot(&LibraryInterface::getDeviceExtensions) == 4);
    CHECK(vtableSlot(&LibraryInterface::getDeviceSubtypes) == 5);
    CHECK(vtableSlot(&LibraryInterface::loadModule) == 6);
    CHECK(vtableSlot(&LibraryInterface::unloadModule) == 7);

    int handleTarget = 0;
    int userTarget = 0;
    destructorRuns = 0;
    deallocations = 0;
    auto* library = new ProbeLibrary(&handleTarget, statusCallbackForLayout, &userTarget);
    void* const* words = reinterpret_cast<void* const*>(static_cast<LibraryInterface*>(library));
    CHECK(words[1] == &handleTarget);  // what the Khronos loader reads on anariUnloadLibrary
    CHECK(words[2] == reinterpret_cast<void*>(&statusCallbackForLayout));
    CHECK(words[3] == &userTarget);

    alignas(ProbeLibrary) unsigned char storage[sizeof(ProbeLibrary)];
    LibraryInterface* inPlace = new (storage) ProbeLibrary(nullptr, nullptr, nullptr);
    vtableEntry(inPlace, 0)(inPlace);
    CHECK(destructorRuns == 1);
    CHECK(deallocations == 0);

    vtableEntry(library, 1)(library);
    CHECK(destructorRuns == 2);
    CHECK(deallocations == 1);
}

TEST_CASE("A handle is the address of the interface subobject") {
    ProbeDevice device;
    DeviceInterface* asInterface = &device;
    CHECK(ripple::abi::deviceFromHandle(ripple::abi::handleFromDevice(asInterface)) == asInterface);
    CHECK(reinterpret_cast<void*>(ripple::abi::handleFromDevice(asInterface)) == static_cast<void*>(asInterface));
}
