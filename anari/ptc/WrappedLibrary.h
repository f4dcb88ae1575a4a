// Loading the ANARI library the compositing device wraps (by its ANARI name, found beside this library or on
// the normal search path), and the extension list the compositing device reports for it.
#pragma once

#include "anari/backend/LibraryInterface.h"

#include <string>

namespace ripple::ptc {

// A loaded library: the object its entry point returned and its dlopen handle. Deleting the object and
// then dlclosing the handle, in that order (as the ANARI loader does), is the owner's job.
struct WrappedLibrary {
    void* dlopenHandle = nullptr;
    abi::LibraryInterface* library = nullptr;
};

// The library named by RIPPLE_PTC_LIBRARY, else "ripple".
std::string defaultWrappedLibraryName();

// Throws std::runtime_error naming the library, every path tried and the reason.
WrappedLibrary loadWrappedLibrary(const std::string& name, ANARIStatusCallback callback, const void* userPtr);
void unloadWrappedLibrary(WrappedLibrary& wrapped);

// What the compositing device offers on top of a wrapped device with these extensions: its own
// KHR_DATA_PARALLEL_MPI, and every wrapped extension except those compositing cannot carry (frame
// channels other than color and depth, and the wrapped frame's completion callback, which fires before
// the composite exists). A NULL-terminated list that stays valid for the process's life.
const char** compositedExtensions(const char** wrappedExtensions);

}  // namespace ripple::ptc
