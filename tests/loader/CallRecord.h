// What the fake device library (FakeDeviceLibrary.cpp) remembers about the last call that reached it, and
// how a test reads it: through anariDeviceGetProcAddress, so the library still exports only one symbol.
#pragma once

#include <cstdint>
#include <type_traits>

namespace loadertest {

struct CallRecord {
    const char* method = nullptr;  // __func__ of the virtual method the last call reached
    int argumentCount = 0;
    uint64_t arguments[8] = {};    // each argument as a word: pointers by address, integers by value
    uint64_t returned = 0;         // what the method returned, as a word; 0 for void methods
    int callCount = 0;             // calls that reached the library or one of its devices
    int liveDevices = 0;
    int liveLibraries = 0;
};

// anariDeviceGetProcAddress(device, callRecordProcName) returns a function of this type.
using CallRecordAccess = const CallRecord* (*)();
inline constexpr const char* callRecordProcName = "loadertestCallRecord";

// Messages the fake library sends through the application's status callback when its library object is
// destroyed and when its code is unmapped (an ELF destructor), so a test can see their order.
inline constexpr const char* libraryDestroyedMessage = "loadertest: library object destroyed";
inline constexpr const char* moduleUnmappedMessage = "loadertest: module unmapped";

// frameReady(frame, throwingWaitMask) throws, to test that the loader keeps exceptions inside.
inline constexpr uint32_t throwingWaitMask = 77;

// LOADERTEST_NEW_LIBRARY=null makes the entry point return NULL, =throw makes it throw.
inline constexpr const char* newLibraryFailureVariable = "LOADERTEST_NEW_LIBRARY";

template <class T>
uint64_t asWord(T value) {
    if constexpr (std::is_pointer_v<T>)
        return reinterpret_cast<uintptr_t>(value);
    else
        return static_cast<uint64_t>(value);
}

}  // namespace loadertest
