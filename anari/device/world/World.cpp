// World parameters ("instance", "surface", "light"; "volume" accepted and ignored) and its "bounds".
#include "anari/device/world/World.h"

#include "anari/device/scene/SceneSync.h"

#include <cstring>

namespace ripple::device {

void World::commit() {
    forgetDependencies();
    instances_ = pullObjects<Instance>("instance", ANARI_INSTANCE);
    surfaces_ = pullObjects<Surface>("surface", ANARI_SURFACE);
    lights_ = pullObjects<Light>("light", ANARI_LIGHT);
    if (has("volume")) {
        (void)getArray("volume");
        reportWarning("volumes are not supported yet; parameter 'volume' is ignored");
    }
}

bool World::getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait) {
    if (name == "bounds" && type == ANARI_FLOAT32_BOX3 && size >= sizeof(glm::vec3) * 2) {
        const bvh::Aabb bounds = worldBounds(*this);
        if (bounds.empty()) return false;  // nothing renderable: no bounds to report
        std::memcpy(mem, &bounds.lo, sizeof(glm::vec3));
        std::memcpy(static_cast<char*>(mem) + sizeof(glm::vec3), &bounds.hi, sizeof(glm::vec3));
        return true;
    }
    return SceneObject::getProperty(name, type, mem, size, wait);
}

}  // namespace ripple::device
