// Slot-and-generation handles for the Ripple device's objects (see HandleTable.h).
#include "anari/device/object/HandleTable.h"

#include <stdexcept>

namespace ripple::device {

uint64_t HandleTable::encode(uint32_t slot, uint32_t generation) {
    return (uint64_t(generation) << 32) | (uint64_t(slot) << 1) | 1u;
}

ANARIObject HandleTable::add(Object* object) {
    std::lock_guard lock(mutex_);
    uint32_t slot;
    if (!freeSlots_.empty()) {
        slot = freeSlots_.back();
        freeSlots_.pop_back();
    } else {
        if (slots_.size() >= (uint64_t(1) << 31)) throw std::length_error("more than 2^31 live ANARI objects");
        slot = uint32_t(slots_.size());
        slots_.emplace_back();
    }
    Slot& entry = slots_[slot];
    entry.object = object;
    ++entry.generation;  // generation 0 is never handed out
    if (entry.generation == 0) entry.generation = 1;
    return reinterpret_cast<ANARIObject>(encode(slot, entry.generation));
}

void HandleTable::remove(ANARIObject handle) {
    std::lock_guard lock(mutex_);
    const auto value = reinterpret_cast<uint64_t>(handle);
    const uint32_t slot = uint32_t(value >> 1) & 0x7fffffffu;
    if ((value & 1u) == 0 || slot >= slots_.size() || slots_[slot].generation != uint32_t(value >> 32) ||
        !slots_[slot].object)
        return;
    slots_[slot].object = nullptr;
    freeSlots_.push_back(slot);
}

Object* HandleTable::find(ANARIObject handle) const {
    std::lock_guard lock(mutex_);
    const auto value = reinterpret_cast<uint64_t>(handle);
    if ((value & 1u) == 0) return nullptr;
    const uint32_t slot = uint32_t(value >> 1) & 0x7fffffffu;
    if (slot >= slots_.size() || slots_[slot].generation != uint32_t(value >> 32)) return nullptr;
    return slots_[slot].object;
}

std::vector<Object*> HandleTable::liveObjects() const {
    std::lock_guard lock(mutex_);
    std::vector<Object*> objects;
    for (const Slot& slot : slots_)
        if (slot.object) objects.push_back(slot.object);
    return objects;
}


}  // namespace ripple::device
