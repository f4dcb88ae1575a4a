// Keeps C++ exceptions from crossing the C API: every loader entry point runs its forwarded call through
// callGuarded, which turns an escaping exception into a message on stderr and a neutral return value.
#pragma once

#include <cstdio>
#include <exception>

namespace ripple::loader {

// A library or device that throws has broken its own contract, and the loader has no status callback of
// the device to report through, so stderr it is; the application sees NULL/0 as for any failed call.
inline void reportEscapedException(const char* function, const char* what) {
    std::fprintf(stderr, "ANARI loader: %s: the device library let an exception escape: %s\n", function, what);
}

template <class Result, class Call>
Result callGuarded(const char* function, Result fallback, Call&& call) noexcept {
    try {
        return call();
    } catch (const std::exception& error) {
        reportEscapedException(function, error.what());
    } catch (...) {
        reportEscapedException(function, "unknown exception");
    }
    return fallback;
}

template <class Call>
void callGuarded(const char* function, Call&& call) noexcept {
    try {
        call();
    } catch (const std::exception& error) {
        reportEscapedException(function, error.what());
    } catch (...) {
        reportEscapedException(function, "unknown exception");
    }
}

}  // namespace ripple::loader
