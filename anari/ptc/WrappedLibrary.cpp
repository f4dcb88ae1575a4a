// Loading the wrapped ANARI library, and the compositing device's extension list (see WrappedLibrary.h).
#include "anari/ptc/WrappedLibrary.h"

#include <dlfcn.h>

#include <cstdlib>
#include <deque>
#include <mutex>
#include <set>
#include <stdexcept>
#include <vector>

namespace ripple::ptc {

namespace {

using NewLibraryFunction = ANARILibrary (*)(void*, ANARIStatusCallback, const void*);

// The folder this library was loaded from, so the wrapped library is found beside it.
std::string ownDirectory() {
    static const char addressInside = 0;
    Dl_info info{};
    if (dladdr(&addressInside, &info) == 0 || info.dli_fname == nullptr) return {};
    const std::string path = info.dli_fname;
    const size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool carriedByCompositing(const std::string& extension) {
    static const std::set<std::string> dropped = {
        "ANARI_KHR_FRAME_CHANNEL_ALBEDO",       "ANARI_KHR_FRAME_CHANNEL_NORMAL",
        "ANARI_KHR_FRAME_CHANNEL_PRIMITIVE_ID", "ANARI_KHR_FRAME_CHANNEL_OBJECT_ID",
        "ANARI_KHR_FRAME_CHANNEL_INSTANCE_ID",  "ANARI_KHR_FRAME_COMPLETION_CALLBACK"};
    return dropped.count(extension) == 0;
}

}  // namespace

std::string defaultWrappedLibraryName() {
    const char* fromEnvironment = std::getenv("RIPPLE_PTC_LIBRARY");
    return fromEnvironment && *fromEnvironment ? fromEnvironment : "ripple";
}

WrappedLibrary loadWrappedLibrary(const std::string& name, ANARIStatusCallback callback, const void* userPtr) {
    const std::string fileName = "libanari_library_" + name + ".so";
    std::string reasons;
    WrappedLibrary wrapped;
    for (const std::string& candidate : {ownDirectory() + fileName, fileName}) {
        dlerror();
        wrapped.dlopenHandle = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
        if (wrapped.dlopenHandle) break;
        const char* reason = dlerror();
        reasons += "\n  " + candidate + ": " + (reason ? reason : "unknown dlopen error");
    }
    if (!wrapped.dlopenHandle)
        throw std::runtime_error("cannot load the wrapped library '" + name + "' (device parameter "
                                 "\"library\" or RIPPLE_PTC_LIBRARY):" + reasons);
    const std::string symbol = "anari_library_" + name + "_new_library";
    auto newLibrary = reinterpret_cast<NewLibraryFunction>(dlsym(wrapped.dlopenHandle, symbol.c_str()));
    ANARILibrary library = newLibrary ? newLibrary(wrapped.dlopenHandle, callback, userPtr) : nullptr;
    if (!library) {
        dlclose(wrapped.dlopenHandle);
        throw std::runtime_error("the wrapped library '" + name + "' " +
                                 (newLibrary ? symbol + " returned NULL" : "does not export " + symbol));
    }
    wrapped.library = abi::libraryFromHandle(library);
    return wrapped;
}

void unloadWrappedLibrary(WrappedLibrary& wrapped) {
    delete wrapped.library;  // like the loader: delete the library object, then unmap its code
    if (wrapped.dlopenHandle) dlclose(wrapped.dlopenHandle);
    wrapped = {};
}

const char** compositedExtensions(const char** wrappedExtensions) {
    // Lists are interned: the same input gives the same pointer, so callers may hold it forever.
    static std::mutex mutex;
    static std::deque<std::string> names;
    static std::vector<std::pair<std::vector<std::string>, std::vector<const char*>>> lists;
    std::vector<std::string> result = {"ANARI_KHR_DATA_PARALLEL_MPI"};
    for (const char** e = wrappedExtensions; e && *e; ++e)
        if (carriedByCompositing(*e) && std::string(*e) != result.front()) result.emplace_back(*e);
    std::lock_guard lock(mutex);
    for (auto& [key, pointers] : lists)
        if (key == result) return pointers.data();
    std::vector<const char*> pointers;
    for (const std::string& extension : result) pointers.push_back(names.emplace_back(extension).c_str());
    pointers.push_back(nullptr);
    lists.emplace_back(std::move(result), std::move(pointers));
    return lists.back().second.data();
}

}  // namespace ripple::ptc
