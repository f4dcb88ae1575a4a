// ANARI arrays: shared application memory or device-managed storage, mapping, privatization and the
// deleter contract.
#include "anari/device/array/Array.h"

#include "anari/device/object/DeviceState.h"

#include <unistd.h>

namespace ripple::device {

namespace {

// Physical memory of this machine: a managed array larger than this cannot be backed, and zero-filling it
// would invite the out-of-memory killer rather than a clean error.
uint64_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return UINT64_MAX;
    return uint64_t(pages) * uint64_t(pageSize);
}

}  // namespace

std::optional<std::string> Array::sizeProblem(ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3,
                                              bool managed) {
    const std::string shape = std::to_string(n1) + " x " + std::to_string(n2) + " x " + std::to_string(n3);
    uint64_t count = 0, bytes = 0;
    if (__builtin_mul_overflow(n1, n2, &count) || __builtin_mul_overflow(count, n3, &count) ||
        __builtin_mul_overflow(count, uint64_t(ripple_anari::sizeOf(elementType)), &bytes) ||
        bytes > uint64_t(PTRDIFF_MAX))
        return "array of " + shape + " elements of " + ripple_anari::typeName(elementType) +
               ": its size in bytes overflows 64 bits";
    if (managed && bytes > physicalMemoryBytes())
        return "array of " + shape + " elements of " + ripple_anari::typeName(elementType) + " needs " +
               std::to_string(bytes) + " bytes, more than this machine's memory (" +
               std::to_string(physicalMemoryBytes()) + " bytes)";
    return std::nullopt;
}

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

void Array::onLastPublicRelease() {
    // Captured memory (with a deleter) is ours until we call the deleter; shared memory is the
    // application's again the moment anariRelease returns, so whatever still uses the array needs a copy.
    if (!appMemory_ || deleter_) return;
    const auto* bytes = static_cast<const uint8_t*>(appMemory_);
    owned_.assign(bytes, bytes + size() * ripple_anari::sizeOf(elementType_));
    appMemory_ = nullptr;
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
    for (Object* object : previous)
        if (object) object->release();
    commitParameters();  // an array's contents are its committed state: stamp it as changed
}

void Array::retainObjectElements() {
    held_.clear();
    if (!ripple_anari::isObjectType(elementType_)) return;
    // The handles are read now, while the application's memory is certainly valid; from here on the array
    // works from the objects it holds, never from the handles in application memory.
    const auto* handles = static_cast<const ANARIObject*>(data());
    held_.resize(size(), nullptr);
    uint64_t stale = 0, wrongType = 0, firstStale = 0, firstWrong = 0;
    std::string wrongLabel;
    for (uint64_t i = 0; i < size(); ++i) {
        if (!handles[i]) continue;
        Object* object = state().handles.find(handles[i]);
        if (!object || object->publicReferenceCount() == 0) {
            if (stale++ == 0) firstStale = i;
            continue;
        }
        const bool anyArray = elementType_ == ANARI_ARRAY && (object->type() == ANARI_ARRAY1D ||
                                                              object->type() == ANARI_ARRAY2D ||
                                                              object->type() == ANARI_ARRAY3D);
        if (elementType_ != ANARI_OBJECT && !anyArray && object->type() != elementType_) {
            if (wrongType++ == 0) {
                firstWrong = i;
                wrongLabel = object->label();
            }
            continue;
        }
        object->retain();
        held_[i] = object;
    }
    if (stale > 0)
        reportError(std::to_string(stale) + " element(s) are not live objects of this device (first: element " +
                    std::to_string(firstStale) + "); they are left out");
    if (wrongType > 0)
        reportError(std::to_string(wrongType) + " element(s) are not of the array's type " +
                    ripple_anari::typeName(elementType_) + " (first: element " + std::to_string(firstWrong) +
                    ", " + wrongLabel + "); they are left out");
}

void Array::releaseObjectElements() {
    std::vector<Object*> held = std::move(held_);
    for (Object* object : held)
        if (object) object->release();
}

}  // namespace ripple::device
