// The one symbol libanari_library_ripple.so exports, and the library object it returns (layout in
// anari/backend/LibraryInterface.h). Any device subtype name is accepted: "default", "ripple", and the
// "distributed" that data-parallel tutorials ask for all give the Ripple device.
#include "anari/backend/LibraryInterface.h"
#include "anari/device/Device.h"
#include "anari/device/Introspection.h"

#include <exception>
#include <string>

namespace ripple::device {

namespace {

class Library final : public abi::LibraryInterface {
public:
    Library(void* handle, ANARIStatusCallback callback, const void* userPtr)
        : LibraryInterface(handle, callback, userPtr) {}
    ~Library() override = default;  // the loader dlcloses after deleting us: never dlclose here

    ANARIDevice newDevice(const char* subtype) override {
        try {
            return (new Device(subtype, defaultStatusCallback, defaultStatusCallbackUserPtr))->handle();
        } catch (const std::exception& error) {
            report(std::string("anariNewDevice: ") + error.what());
            return nullptr;
        }
    }

    ANARIDevice newInitializedDevice(const char* subtype, ANARIParameterValue* initializers) override {
        ANARIDevice device = newDevice(subtype);
        if (!device) return nullptr;
        auto* deviceObject = abi::deviceFromHandle(device);
        for (ANARIParameterValue* p = initializers; p && p->name; ++p)
            deviceObject->setParameter(device, p->name, p->type, p->value);
        deviceObject->commitParameters(device);
        return device;
    }

    const char** getDeviceExtensions(const char*) override { return deviceExtensions(); }
    const char** getDeviceSubtypes() override { return deviceSubtypes(); }

    void loadModule(const char* name) override {
        report(std::string("anariLoadModule: Ripple has no modules ('") + (name ? name : "NULL") + "')");
    }
    void unloadModule(const char*) override {}

private:
    void report(const std::string& message) const {
        if (defaultStatusCallback)
            defaultStatusCallback(defaultStatusCallbackUserPtr, nullptr, nullptr, ANARI_LIBRARY,
                                  ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_OPERATION, message.c_str());
    }
};

}  // namespace

}  // namespace ripple::device

extern "C" __attribute__((visibility("default"))) ANARILibrary anari_library_ripple_new_library(
    void* dlopenHandle, ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr) {
    try {
        return ripple::abi::handleFromLibrary(
            new ripple::device::Library(dlopenHandle, defaultCallback, defaultCallbackUserPtr));
    } catch (...) {
        return nullptr;
    }
}
