// ANARI arrays (1D/2D/3D): application-owned memory with an optional deleter (called exactly once, when
// the array dies), or managed memory the device allocates (appMemory NULL). Mapping returns the memory
// to write; unmapping stamps the array as changed so whatever uses it is rebuilt. When the application
// releases its last reference to a shared array that the device still uses, the array copies the data
// ("privatizes"): the application may free its memory as soon as anariRelease returns.
#pragma once

#include "anari/device/object/Object.h"

#include <optional>
#include <span>

namespace ripple::device {

class Array : public Object {
public:
    Array(DeviceState& state, ANARIDataType arrayType, const void* appMemory, ANARIMemoryDeleter deleter,
          const void* deleterUserData, ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3);
    ~Array() override;

    // The array's size in bytes, or a message naming the problem: an element count or byte size that
    // overflows 64 bits, or managed memory larger than the machine has. Checked before construction.
    static std::optional<std::string> sizeProblem(ANARIDataType elementType, uint64_t n1, uint64_t n2, uint64_t n3,
                                                  bool managed);

    ANARIDataType elementType() const { return elementType_; }
    uint64_t size() const { return dims_[0] * dims_[1] * dims_[2]; }
    uint64_t dim(int axis) const { return dims_[axis]; }
    const void* data() const { return appMemory_ ? appMemory_ : owned_.data(); }

    // The elements as T when the element type matches exactly (checked by the caller with elementType()).
    template <class T> std::span<const T> as() const {
        return {static_cast<const T*>(data()), static_cast<size_t>(size())};
    }

    void* map();
    void unmap();
    bool mapped() const { return mapped_; }
    // Object elements (arrays of ANARI_SURFACE, ANARI_INSTANCE...), one per element in order (nullptr for
    // NULL handles and for handles that were not live objects, which are reported), retained by the array
    // from its creation (and each unmap) on: a released object inside a live array stays alive.
    std::span<Object* const> objects() const { return held_; }

    void dropReferences() override {
        Object::dropReferences();
        releaseObjectElements();
    }

protected:
    void onLastPublicRelease() override;

private:
    ANARIDataType elementType_;
    uint64_t dims_[3];
    const void* appMemory_;
    ANARIMemoryDeleter deleter_;
    const void* deleterUserData_;
    std::vector<uint8_t> owned_;
    bool mapped_ = false;
    std::vector<Object*> held_;          // object elements retained by the array
    void retainObjectElements();
    void releaseObjectElements();
};

}  // namespace ripple::device
