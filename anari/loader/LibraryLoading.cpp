// The library half of the C API: finding and dlopening libanari_library_NAME.so, creating its library object
// through the one symbol it exports, and forwarding library calls to ripple::abi::LibraryInterface.
#include "anari/anari.h"
#include "anari/backend/LibraryInterface.h"
#include "CallGuard.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using ripple::abi::LibraryInterface;
using ripple::loader::callGuarded;

namespace {

using NewLibraryFunction = ANARILibrary (*)(void* dlopenHandle, ANARIStatusCallback defaultCallback,
                                            const void* defaultCallbackUserPtr);

// No library exists yet to carry a callback, so failures go to the one the application passed in.
void reportLoadError(ANARIStatusCallback callback, const void* userPtr, const std::string& message) {
    if (callback != nullptr) {
        callback(userPtr, nullptr, nullptr, ANARI_LIBRARY, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT,
                 message.c_str());
    } else {
        std::fprintf(stderr, "ANARI loader: %s\n", message.c_str());
    }
}

// The folder libanari.so was loaded from (with a trailing '/'), so device libraries installed beside it are
// found without LD_LIBRARY_PATH; empty if the dynamic linker cannot say.
std::string loaderDirectory() {
    static const char addressInsideLoader = 0;
    Dl_info info{};
    if (dladdr(&addressInsideLoader, &info) == 0 || info.dli_fname == nullptr) return {};
    const std::string path = info.dli_fname;
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

struct LibrarySpec {
    std::string name;       // NAME in libanari_library_NAME.so and anari_library_NAME_new_library
    std::string directory;  // from "NAME,/dir/"; empty: search path, then the loader's folder
};

// Accepts "NAME", "NAME,/dir/" and "environment" (NAME, or NAME,/dir/, taken from ANARI_LIBRARY).
bool parseLibrarySpec(const char* requested, LibrarySpec& spec, std::string& error) {
    if (requested == nullptr) {
        error = "anariLoadLibrary: the library name is NULL";
        return false;
    }
    std::string text = requested;
    if (text == "environment") {
        const char* fromEnvironment = std::getenv("ANARI_LIBRARY");
        if (fromEnvironment == nullptr || *fromEnvironment == '\0') {
            error = "anariLoadLibrary(\"environment\"): the variable ANARI_LIBRARY is not set";
            return false;
        }
        text = fromEnvironment;
    }
    const size_t comma = text.find(',');
    spec.name = text.substr(0, comma);
    spec.directory = comma == std::string::npos ? std::string() : text.substr(comma + 1);
    if (spec.name.empty() || spec.name.find('/') != std::string::npos) {
        error = "anariLoadLibrary(\"" + std::string(requested) + "\"): '" + spec.name +
                "' is not a library name (expected NAME or NAME,/directory/)";
        return false;
    }
    if (!spec.directory.empty() && spec.directory.back() != '/') spec.directory += '/';
    return true;
}

// dlopens the first candidate that loads; on failure `error` holds every candidate's dlerror text.
void* openLibraryFile(const LibrarySpec& spec, std::string& error) {
    const std::string fileName = "libanari_library_" + spec.name + ".so";
    std::vector<std::string> candidates;
    if (!spec.directory.empty()) {
        candidates.push_back(spec.directory + fileName);
    } else {
        candidates.push_back(fileName);
        const std::string besideLoader = loaderDirectory();
        if (!besideLoader.empty()) candidates.push_back(besideLoader + fileName);
    }
    error = "anariLoadLibrary: cannot load library '" + spec.name + "' (" + fileName + "):";
    for (const std::string& candidate : candidates) {
        dlerror();
        if (void* handle = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL)) return handle;
        const char* reason = dlerror();
        error += "\n  " + candidate + ": " + (reason != nullptr ? reason : "unknown dlopen error");
    }
    return nullptr;
}

LibraryInterface* libraryOf(ANARILibrary library) { return ripple::abi::libraryFromHandle(library); }

}  // namespace

ANARILibrary anariLoadLibrary(const char* name, ANARIStatusCallback statusCallback,
                              const void* statusCallbackUserData) {
    LibrarySpec spec;
    std::string error;
    if (!parseLibrarySpec(name, spec, error)) {
        reportLoadError(statusCallback, statusCallbackUserData, error);
        return nullptr;
    }
    void* dlopenHandle = openLibraryFile(spec, error);
    if (dlopenHandle == nullptr) {
        reportLoadError(statusCallback, statusCallbackUserData, error);
        return nullptr;
    }
    const std::string symbol = "anari_library_" + spec.name + "_new_library";
    dlerror();
    void* address = dlsym(dlopenHandle, symbol.c_str());
    if (address == nullptr) {
        reportLoadError(statusCallback, statusCallbackUserData,
                        "anariLoadLibrary: library '" + spec.name + "' was found but does not export " + symbol);
        dlclose(dlopenHandle);
        return nullptr;
    }
    const auto newLibrary = reinterpret_cast<NewLibraryFunction>(address);
    ANARILibrary library = callGuarded(__func__, ANARILibrary{nullptr}, [&] {
        return newLibrary(dlopenHandle, statusCallback, statusCallbackUserData);
    });
    if (library == nullptr) {
        reportLoadError(statusCallback, statusCallbackUserData,
                        "anariLoadLibrary: " + symbol + " of library '" + spec.name + "' returned NULL");
        dlclose(dlopenHandle);
        return nullptr;
    }
    return library;
}

// The handle is read before the object is deleted, and the code is unmapped only after its destructor ran.
void anariUnloadLibrary(ANARILibrary library) {
    if (library == nullptr) return;
    void* dlopenHandle = libraryOf(library)->dlopenHandle;
    callGuarded(__func__, [&] { delete libraryOf(library); });
    if (dlopenHandle != nullptr) dlclose(dlopenHandle);
}

void anariLoadModule(ANARILibrary library, const char* name) {
    if (library == nullptr) return;
    callGuarded(__func__, [&] { libraryOf(library)->loadModule(name); });
}

void anariUnloadModule(ANARILibrary library, const char* name) {
    if (library == nullptr) return;
    callGuarded(__func__, [&] { libraryOf(library)->unloadModule(name); });
}

ANARIDevice anariNewDevice(ANARILibrary library, const char* type) {
    if (library == nullptr) return nullptr;
    return callGuarded(__func__, ANARIDevice{nullptr}, [&] { return libraryOf(library)->newDevice(type); });
}

ANARIDevice anariNewInitializedDevice(ANARILibrary library, const char* type, ANARIParameterValue* initializers) {
    if (library == nullptr) return nullptr;
    return callGuarded(__func__, ANARIDevice{nullptr},
                       [&] { return libraryOf(library)->newInitializedDevice(type, initializers); });
}

const char** anariGetDeviceSubtypes(ANARILibrary library) {
    if (library == nullptr) return nullptr;
    return callGuarded(__func__, static_cast<const char**>(nullptr),
                       [&] { return libraryOf(library)->getDeviceSubtypes(); });
}

const char** anariGetDeviceExtensions(ANARILibrary library, const char* deviceSubtype) {
    if (library == nullptr) return nullptr;
    return callGuarded(__func__, static_cast<const char**>(nullptr),
                       [&] { return libraryOf(library)->getDeviceExtensions(deviceSubtype); });
}
