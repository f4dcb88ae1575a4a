// Base of the objects a world is built from: each remembers the arrays and child objects its last commit
// used, so SceneSync can tell what changed since the last frame without the application recommitting.
#pragma once

#include "anari/device/array/Array.h"
#include "anari/device/object/Object.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ripple::device {

// A counted reference held by committed state: an object the application releases or unsets after a
// commit stays alive while a parent still renders with it. API thread only (the count is not atomic).
template <class T>
class ObjectRef {
public:
    ObjectRef() = default;
    explicit ObjectRef(T* object) : object_(object) {
        if (object_) object_->retain();
    }
    ObjectRef(const ObjectRef& other) : ObjectRef(other.object_) {}
    ObjectRef(ObjectRef&& other) noexcept : object_(std::exchange(other.object_, nullptr)) {}
    ObjectRef& operator=(ObjectRef other) noexcept {
        std::swap(object_, other.object_);
        return *this;
    }
    ~ObjectRef() {
        if (object_) object_->release();
    }

    T* get() const { return object_; }
    T* operator->() const { return object_; }
    T& operator*() const { return *object_; }
    explicit operator bool() const { return object_ != nullptr; }

private:
    T* object_ = nullptr;
};

class SceneObject : public Object {
public:
    using Object::Object;

    // The largest stamp in this object's committed subtree: its own commit, its arrays' unmaps and its
    // children's subtrees. An object whose arrays were rewritten after its commit is committed again first,
    // so nothing renders from stale or freed data. API thread only. One walk (same walk number) visits a
    // shared subtree once, however many parents it has.
    uint64_t refreshSubtree(uint64_t walk);
    static uint64_t newWalk();

    void dropReferences() override {
        Object::dropReferences();
        forgetDependencies();
    }

protected:
    // commit() starts with forgetDependencies() and records what it keeps with useArray/useChild.
    void forgetDependencies();
    void useArray(Array* array);
    void useChild(SceneObject* child);
    // The elements of class T of an optional ARRAY1D parameter of `elementType` handles, recorded as
    // dependencies. Null elements and elements of unknown subtypes (already reported) are skipped.
    template <class T>
    std::vector<T*> pullObjects(std::string_view name, ANARIDataType elementType);

private:
    std::vector<ObjectRef<Array>> arrays_;
    std::vector<ObjectRef<SceneObject>> children_;
    uint64_t lastWalk_ = 0;
    uint64_t newestInLastWalk_ = 0;
};

template <class T>
std::vector<T*> SceneObject::pullObjects(std::string_view name, ANARIDataType elementType) {
    std::vector<T*> objects;
    if (!has(name)) return objects;
    Array* array = getArray(name);
    if (!array) return objects;  // the wrong type was reported by getArray
    if (array->elementType() != elementType) {
        reportWarning("parameter '" + std::string(name) + "' holds " + ripple_anari::typeName(array->elementType()) +
                      ", expected " + ripple_anari::typeName(elementType) + "; ignored");
        return objects;
    }
    useArray(array);
    for (Object* element : array->objects()) {
        if (T* object = dynamic_cast<T*>(element)) {
            useChild(object);
            objects.push_back(object);
        }
    }
    return objects;
}

}  // namespace ripple::device
