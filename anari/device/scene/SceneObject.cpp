// Change tracking of committed world objects (see SceneObject.h).
#include "anari/device/scene/SceneObject.h"

#include <algorithm>
#include <atomic>

namespace ripple::device {

uint64_t SceneObject::newWalk() {
    static std::atomic<uint64_t> walks{0};
    return ++walks;
}

uint64_t SceneObject::refreshSubtree(uint64_t walk) {
    if (walk == lastWalk_) return newestInLastWalk_;
    const bool arrayChanged = std::any_of(arrays_.begin(), arrays_.end(), [&](const ObjectRef<Array>& array) {
        return array->lastCommitted() > lastCommitted();
    });
    if (arrayChanged) commitParameters();

    uint64_t newest = lastCommitted();
    for (const ObjectRef<Array>& array : arrays_) newest = std::max(newest, array->lastCommitted());
    for (const ObjectRef<SceneObject>& child : children_) newest = std::max(newest, child->refreshSubtree(walk));
    lastWalk_ = walk;
    newestInLastWalk_ = newest;
    return newest;
}

void SceneObject::forgetDependencies() {
    arrays_.clear();
    children_.clear();
}

void SceneObject::useArray(Array* array) {
    if (array) arrays_.emplace_back(array);
}

void SceneObject::useChild(SceneObject* child) {
    if (child) children_.emplace_back(child);
}

}  // namespace ripple::device
