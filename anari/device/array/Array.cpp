// ANARI arrays: shared application memory or device-managed storage, mapping, and the deleter contract.
#include "anari/device/array/Array.h"

#include "anari/device/object/DeviceState.h"

namespace ripple::device {

Array::Array(DeviceState& state, ANARIDataType arrayType, const void* appMemory, ANARIMemoryDeleter deleter,
             const void* deleterUserData, ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3)
    : Object(state, arrayType, ""),
      elementType_(elementType),
      dims_{n1, n2, n3},
      appMemory_(appMemory),
      deleter_(deleter),
      deleterUserData_(deleterUserData) {
    if (!appMemory_) owned_.assign(size() * ripple_anari::sizeOf(elementType_), 0);
    retainObjectElements();
}

Array::~Array() {
    releaseObjectElements();
    if (appMemory_ && deleter_) deleter_(deleterUserData_, appMemory_);  // exactly once, here
}

std::span<Object* const> Array::objects() const {
    if (!ripple_anari::isObjectType(elementType_)) return {};
    return {static_cast<Object* const*>(data()), static_cast<size_t>(size())};
}

void* Array::map() {
    if (mapped_) reportWarning("mapped twice without an unmap in between");
    mapped_ = true;
    return const_cast<void*>(data());
}

void Array::unmap() {
    if (!mapped_) {
        reportWarning("unmapped without being mapped; ignored");
        return;
    }
    mapped_ = false;
    // Object elements may have been replaced through the mapping: hold the new set, then let go of the
    // old one (in this order, so an element present in both never drops to zero references).
    std::vector<Object*> previous = std::move(held_);
    retainObjectElements();
    for (Object* object : previous) object->release();
    commitParameters();  // an array's contents are its committed state: stamp it as changed
}

void Array::retainObjectElements() {
    held_.clear();
    for (Object* object : objects()) {
        if (!object) continue;
        object->retain();
        held_.push_back(object);
    }
}

void Array::releaseObjectElements() {
    std::vector<Object*> held = std::move(held_);
    for (Object* object : held) object->release();
}

}  // namespace ripple::device
