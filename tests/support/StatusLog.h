// Collects what a library or device reports through the ANARI status callback, so tests can assert on
// messages: every suite's one status log. A log that a fake library may still report to after its test
// returns lives in static storage (see the loader tests).
#pragma once

#include "anari/anari.h"

#include <mutex>
#include <string>
#include <vector>

namespace ripple::test {

struct StatusLog {
    struct Entry {
        ANARIDataType sourceType;
        ANARIStatusSeverity severity;
        ANARIStatusCode code;
        std::string message;
    };
    std::mutex mutex;
    std::vector<Entry> entries;

    // The userPtr given with the callback is the StatusLog.
    static void callback(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType sourceType,
                         ANARIStatusSeverity severity, ANARIStatusCode code, const char* message) {
        auto* log = const_cast<StatusLog*>(static_cast<const StatusLog*>(userPtr));
        std::lock_guard lock(log->mutex);
        log->entries.push_back({sourceType, severity, code, message ? message : "(null)"});
    }

    // Index of the first entry (any severity) whose message contains `text`, or -1.
    int find(const char* text) {
        std::lock_guard lock(mutex);
        for (size_t i = 0; i < entries.size(); ++i)
            if (entries[i].message.find(text) != std::string::npos) return int(i);
        return -1;
    }
    size_t size() {
        std::lock_guard lock(mutex);
        return entries.size();
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
    // Entries at ERROR severity or worse.
    size_t errors() {
        std::lock_guard lock(mutex);
        size_t n = 0;
        for (const Entry& e : entries) n += e.severity <= ANARI_SEVERITY_ERROR ? 1 : 0;
        return n;
    }
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

// One log with static storage, emptied on each call: for a library that may report after its test returns
// (the loader tests' fake library reports from its unload hook).
inline StatusLog& freshStaticStatusLog() {
    static StatusLog log;
    log.clear();
    return log;
}

}  // namespace ripple::test
