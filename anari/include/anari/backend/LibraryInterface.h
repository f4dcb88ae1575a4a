// The library object a device library returns from anari_library_NAME_new_library, laid out (Itanium C++
// ABI) as the Khronos SDK's loader expects, so that loader and Ripple's own can both drive it.
#pragma once

#include <cstddef>

#include "anari/anari.h"

namespace ripple::abi {

// Layout the loaders rely on: vtable pointer at offset 0, dlopenHandle at offset 8 (read by
// anariUnloadLibrary, which deletes the object and then dlcloses: the destructor must not dlclose).
// Virtual slots, in declaration order: 0-1 destructor (complete, deleting), 2 newDevice,
// 3 newInitializedDevice, 4 getDeviceExtensions, 5 getDeviceSubtypes, 6 loadModule, 7 unloadModule.
// Do not add, remove or reorder virtual functions.
class LibraryInterface {
public:
    virtual ~LibraryInterface() = default;

    virtual ANARIDevice newDevice(const char* subtype) = 0;
    virtual ANARIDevice newInitializedDevice(const char* subtype, ANARIParameterValue* initializers) = 0;
    virtual const char** getDeviceExtensions(const char* deviceSubtype) = 0;
    virtual const char** getDeviceSubtypes() = 0;
    virtual void loadModule(const char* name) = 0;
    virtual void unloadModule(const char* name) = 0;

    LibraryInterface(const LibraryInterface&) = delete;
    LibraryInterface& operator=(const LibraryInterface&) = delete;

    void* dlopenHandle;
    ANARIStatusCallback defaultStatusCallback;
    const void* defaultStatusCallbackUserPtr;

protected:
    LibraryInterface(void* dlopenHandleIn, ANARIStatusCallback defaultStatusCallbackIn,
                     const void* defaultStatusCallbackUserPtrIn)
        : dlopenHandle(dlopenHandleIn),
          defaultStatusCallback(defaultStatusCallbackIn),
          defaultStatusCallbackUserPtr(defaultStatusCallbackUserPtrIn) {}
};

// The class is not standard-layout (it has virtual functions), so offsetof is only "conditionally
// supported"; g++ and clang compute it for single inheritance without virtual bases, which is the case here.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
#endif
static_assert(offsetof(LibraryInterface, dlopenHandle) == 8, "the loaders read the dlopen handle at offset 8");
static_assert(offsetof(LibraryInterface, defaultStatusCallback) == 16);
static_assert(offsetof(LibraryInterface, defaultStatusCallbackUserPtr) == 24);
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

// The handle an application holds is the address of the LibraryInterface subobject.
inline LibraryInterface* libraryFromHandle(ANARILibrary library) {
    return reinterpret_cast<LibraryInterface*>(library);
}
inline ANARILibrary handleFromLibrary(LibraryInterface* library) {
    return reinterpret_cast<ANARILibrary>(library);
}

}  // namespace ripple::abi
