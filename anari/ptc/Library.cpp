// The one symbol libanari_library_ripple_ptc.so exports, and its library object: every device subtype
// gives a pass-through compositing device (anari/ptc/PtcDevice.h).
#include "anari/backend/LibraryInterface.h"
#include "anari/ptc/PtcDevice.h"

namespace ripple::ptc {

namespace {

const char* deviceSubtypeNames[] = {"default", nullptr};
const char* noExtensions[] = {nullptr};

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
    // The wrapped device's extensions are known only once it is loaded: none are promised here.
    const char** getDeviceExtensions(const char*) override { return noExtensions; }
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
