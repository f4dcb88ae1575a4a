// One ANARI device as the Python module holds it: the library and device handles, the device's status
// messages turned into Python warnings and exceptions, and the numpy arrays the device shares.
#pragma once

#include <anari/anari.h>

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ripple::python {

namespace py = pybind11;

// Raised (as pynari.DeviceError, a RuntimeError) when the device reports an error.
struct DeviceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class DeviceSession {
public:
    // Loads `libraryName` ("default": ANARI_LIBRARY, else ripple) and creates its device of `subtype`.
    DeviceSession(const std::string& libraryName, const std::string& subtype);
    ~DeviceSession();
    DeviceSession(const DeviceSession&) = delete;
    DeviceSession& operator=(const DeviceSession&) = delete;

    ANARIDevice handle() const { return device_; }

    // Turns the messages the device reported since the last call into Python: warnings (DeviceWarning)
    // for warnings, a DeviceError for errors, prefixed by `during` (the call, e.g. "frame.render()").
    // Also drops the numpy arrays the device gave back from another thread. Needs the GIL.
    void raiseStatus(const std::string& during);

    // The ANARI memory deleter of a numpy array shared with the device: userData is the array, whose
    // reference the device held. Any thread; the reference is dropped at once only when this thread holds
    // the GIL, otherwise at the next call of the module.
    static void releaseSharedArray(const void* userData, const void* appMemory);

private:
    static void statusCallback(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType,
                               ANARIStatusSeverity severity, ANARIStatusCode, const char* message);

    struct Message {
        int severity;
        std::string text;
    };
    std::mutex mutex_;
    std::vector<Message> messages_;
    ANARILibrary library_ = nullptr;
    ANARIDevice device_ = nullptr;
};

// Drops the numpy arrays the device gave back from a thread without the GIL. Needs the GIL.
void releasePendingArrays();

}  // namespace ripple::python
