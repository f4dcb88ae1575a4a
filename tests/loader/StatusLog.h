// A status callback for the loader tests that keeps every message in plain storage (safe even if the fake
// library's unload hook calls it late) and helpers to search what it kept.
#pragma once

#include "anari/anari.h"

#include <cstring>
#include <string>

namespace loadertest {

struct StatusLog {
    struct Entry {
        ANARIDataType sourceType;
        ANARIStatusSeverity severity;
        ANARIStatusCode code;
        char message[1024];
    };
    int count = 0;
    Entry entries[16] = {};

    // Index of the first entry whose message contains `text`, or -1.
    int find(const char* text) const {
        for (int index = 0; index < count && index < 16; ++index)
            if (std::strstr(entries[index].message, text) != nullptr) return index;
        return -1;
    }
    int errors() const {
        int errorCount = 0;
        for (int index = 0; index < count && index < 16; ++index)
            errorCount += entries[index].severity <= ANARI_SEVERITY_ERROR ? 1 : 0;
        return errorCount;
    }
};

// The userPtr given to anariLoadLibrary is the StatusLog, so this also checks that it reaches the callback.
inline void recordStatus(const void* userPtr, ANARIDevice, ANARIObject, ANARIDataType sourceType,
                         ANARIStatusSeverity severity, ANARIStatusCode code, const char* message) {
    auto* log = static_cast<StatusLog*>(const_cast<void*>(userPtr));
    if (log->count < 16) {
        StatusLog::Entry& entry = log->entries[log->count];
        entry.sourceType = sourceType;
        entry.severity = severity;
        entry.code = code;
        std::strncpy(entry.message, message != nullptr ? message : "(null)", sizeof entry.message - 1);
    }
    ++log->count;
}

// One log with static storage, emptied by each test: the fake library may report after a test returns.
inline StatusLog& freshStatusLog() {
    static StatusLog log;
    log = StatusLog{};
    return log;
}

}  // namespace loadertest
