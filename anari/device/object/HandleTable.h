// The handles Ripple gives the application: a slot index and a generation, never a pointer. A handle whose
// object has gone (released once too often, or never made by this device) is recognised and reported
// instead of being followed into freed memory.
#pragma once

#include "anari/anari.h"

#include <cstdint>
#include <mutex>
#include <vector>

namespace ripple::device {

class Object;

class HandleTable {
public:
    // A new handle for a live object; never equal to an earlier one of the same slot.
    ANARIObject add(Object* object);
    // The slot becomes free; its handle stops resolving at once.
    void remove(ANARIObject handle);
    // The object behind a handle, or nullptr when the handle is not (or no longer) one of ours.
    Object* find(ANARIObject handle) const;
    std::vector<Object*> liveObjects() const;

private:
    struct Slot {
        Object* object = nullptr;
        uint32_t generation = 0;
    };
    // A handle is (generation << 32) | (slot << 1) | 1: odd, so it can never equal an object or device
    // pointer (those are aligned), and 0 (NULL) is never produced.
    static uint64_t encode(uint32_t slot, uint32_t generation);

    mutable std::mutex mutex_;  // objects die on frame worker threads too
    std::vector<Slot> slots_;
    std::vector<uint32_t> freeSlots_;
};

}  // namespace ripple::device
