// Collects what a device reports through the ANARI status callback, so tests can assert on messages.
#pragma once

#include "anari/anari.h"

#include <mutex>
#include <string>
#include <vector>

namespace ripple::test {

struct StatusLog {
    struct Entry {
        ANARIStatusSeverity severity;
        std::string message;
    };
    std::mutex mutex;
    std::vector<Entry> entries;

    static void callback(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                         ANARIStatusCode, const char* message) {
        auto* log = const_cast<StatusLog*>(static_cast<const StatusLog*>(userPtr));
        std::lock_guard lock(log->mutex);
        log->entries.push_back({severity, message ? message : ""});
    }

    // Messages at WARNING or worse that contain every one of the given fragments.
    size_t count(std::initializer_list<const char*> fragments) {
        std::lock_guard lock(mutex);
        size_t n = 0;
        for (const Entry& e : entries) {
            if (e.severity > ANARI_SEVERITY_WARNING) continue;
            bool all = true;
            for (const char* f : fragments) all = all && e.message.find(f) != std::string::npos;
            n += all ? 1 : 0;
        }
        return n;
    }
    size_t problems() { return count({}); }
    std::string dump() {
        std::lock_guard lock(mutex);
        std::string text;
        // Appended piece by piece: GCC 12 at -O3 warns falsely (-Wrestrict) on "[" + std::to_string(...).
        for (const Entry& e : entries)
            text.append("[").append(std::to_string(e.severity)).append("] ").append(e.message).append("\n");
        return text;
    }
    void clear() {
        std::lock_guard lock(mutex);
        entries.clear();
    }
};

}  // namespace ripple::test
