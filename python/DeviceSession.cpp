// Loading the ANARI library, and the device's status messages as Python warnings and exceptions.
#include "python/DeviceSession.h"

#include <cstdlib>

namespace ripple::python {

namespace {

// numpy arrays whose device reference ended on a thread without the GIL, dropped by the next call.
std::mutex pendingMutex;
std::vector<PyObject*> pendingArrays;

std::string resolveLibraryName(const std::string& requested) {
    if (requested != "default" && requested != "<default>") return requested;
    const char* fromEnvironment = std::getenv("ANARI_LIBRARY");
    return fromEnvironment != nullptr && *fromEnvironment != '\0' ? fromEnvironment : "ripple";
}

}  // namespace

void releasePendingArrays() {
    std::vector<PyObject*> arrays;
    {
        std::lock_guard lock(pendingMutex);
        arrays.swap(pendingArrays);
    }
    for (PyObject* array : arrays) Py_DECREF(array);
}

void DeviceSession::releaseSharedArray(const void* userData, const void*) {
    auto* array = static_cast<PyObject*>(const_cast<void*>(userData));
    if (!Py_IsInitialized()) return;  // at exit: the interpreter and its arrays are gone already
    if (PyGILState_Check()) {
        Py_DECREF(array);
        return;
    }
    // Taking the GIL here could deadlock against a Python thread waiting on the device.
    std::lock_guard lock(pendingMutex);
    pendingArrays.push_back(array);
}

void DeviceSession::statusCallback(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType,
                                   ANARIStatusSeverity severity, ANARIStatusCode, const char* message) {
    // Info and debug messages are the device's log, not the application's business.
    if (severity > ANARI_SEVERITY_PERFORMANCE_WARNING || userPtr == nullptr) return;
    auto* session = static_cast<DeviceSession*>(const_cast<void*>(userPtr));
    std::lock_guard lock(session->mutex_);
    session->messages_.push_back({severity, message != nullptr ? message : "(no message)"});
}

DeviceSession::DeviceSession(const std::string& libraryName, const std::string& subtype) {
    const std::string name = resolveLibraryName(libraryName);
    library_ = anariLoadLibrary(name.c_str(), &DeviceSession::statusCallback, this);
    if (library_ == nullptr) {
        std::string text = "could not load the ANARI library '" + name + "'";
        for (const Message& m : messages_) text += "\n" + m.text;
        throw DeviceError(text);
    }
    device_ = anariNewDevice(library_, subtype.c_str());
    if (device_ == nullptr) {
        std::string text = "the ANARI library '" + name + "' has no device '" + subtype + "'";
        for (const Message& m : messages_) text += "\n" + m.text;
        anariUnloadLibrary(library_);
        throw DeviceError(text);
    }
    messages_.clear();
}

DeviceSession::~DeviceSession() {
    // The last Python object of this device is gone; the device may still hand back shared arrays.
    anariRelease(device_, device_);
    anariUnloadLibrary(library_);
    if (Py_IsInitialized() && PyGILState_Check()) releasePendingArrays();
}

void DeviceSession::raiseStatus(const std::string& during) {
    releasePendingArrays();
    std::vector<Message> messages;
    {
        std::lock_guard lock(mutex_);
        messages.swap(messages_);
    }
    std::string errors;
    static py::handle warningType = py::module_::import("pynari").attr("DeviceWarning");
    for (const Message& m : messages) {
        if (m.severity <= ANARI_SEVERITY_ERROR) {
            errors += (errors.empty() ? "" : "\n") + m.text;
        } else if (PyErr_WarnEx(warningType.ptr(), (during + ": " + m.text).c_str(), 1) != 0) {
            throw py::error_already_set();  // warnings turned into errors by the application's filter
        }
    }
    if (!errors.empty()) throw DeviceError(during + ": " + errors);
}

}  // namespace ripple::python
