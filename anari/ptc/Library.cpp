// The one symbol libanari_library_ripple_ptc.so exports, and its library object: every device subtype
// gives a pass-through compositing device (anari/ptc/PtcDevice.h).
#include "anari/backend/LibraryInterface.h"
#include "anari/ptc/PtcDevice.h"
#include "anari/ptc/WrappedLibrary.h"

#include <exception>
#include <string>

namespace ripple::ptc {

namespace {

const char* deviceSubtypeNames[] = {"default", nullptr};

class Library final : public abi::LibraryInterface {
public:
    Library(void* handle, ANARIStatusCallback callback, const void* userPtr)
        : LibraryInterface(handle, callback, userPtr) {}
    ~Library() override = default;  // the loader dlcloses after deleting us

    ANARIDevice newDevice(const char*) override {
        try {
            return (new PtcDevice(defaultStatusCallback, defaultStatusCallbackUserPtr))->handle();
        } catch (...) {
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
    // The wrapped library (RIPPLE_PTC_LIBRARY, else ripple) is loaded for the question and let go again; a
    // device parameter "library" naming another one is known only to the device's "extension" property.
    const char** getDeviceExtensions(const char*) override {
        try {
            WrappedLibrary wrapped = loadWrappedLibrary(defaultWrappedLibraryName(), defaultStatusCallback,
                                                        defaultStatusCallbackUserPtr);
            const char** list = compositedExtensions(wrapped.library->getDeviceExtensions("default"));
            unloadWrappedLibrary(wrapped);
            return list;
        } catch (const std::exception& error) {
            if (defaultStatusCallback)
                defaultStatusCallback(defaultStatusCallbackUserPtr, nullptr, nullptr, ANARI_LIBRARY,
                                      ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_OPERATION,
                                      (std::string("ripple_ptc: ") + error.what()).c_str());
            return compositedExtensions(nullptr);
        }
    }
    const char** getDeviceSubtypes() override { return deviceSubtypeNames; }
    void loadModule(const char*) override {}
    void unloadModule(const char*) override {}
};

}  // namespace

}  // namespace ripple::ptc

extern "C" __attribute__((visibility("default"))) ANARILibrary anari_library_ripple_ptc_new_library(
    void* dlopenHandle, ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr) {
    try {
        return ripple::abi::handleFromLibrary(
            new ripple::ptc::Library(dlopenHandle, defaultCallback, defaultCallbackUserPtr));
    } catch (...) {
        return nullptr;
    }
}
