// World parameters ("instance", "surface", "volume", "light") and its "bounds".
#include "anari/device/world/World.h"

#include "anari/device/object/DeviceState.h"
#include "anari/device/scene/SceneSync.h"

#include <cstring>
#include <span>

namespace ripple::device {

World::World(DeviceState& state) : SceneObject(state, ANARI_WORLD, ""), globalIndex_(state.nextWorldIndex()) {}

void World::commit() {
    forgetDependencies();
    instances_ = pullObjects<Instance>("instance", ANARI_INSTANCE);
    surfaces_ = pullObjects<Surface>("surface", ANARI_SURFACE);
    lights_ = pullObjects<Light>("light", ANARI_LIGHT);
    volumes_ = pullObjects<Volume>("volume", ANARI_VOLUME);
}

bool World::getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait) {
    if (name == "bounds" && type == ANARI_FLOAT32_BOX3 && size >= sizeof(glm::vec3) * 2) {
        bvh::Aabb bounds = worldBounds(*this);
        // Data-parallel: with ANARI_WAIT the call is collective and the bounds are the union over ranks.
        if (wait && state().communicator().distributed()) {
            state().communicator().min(std::span<float>(&bounds.lo.x, 3));
            state().communicator().max(std::span<float>(&bounds.hi.x, 3));
        }
        if (bounds.empty()) return false;  // nothing renderable: no bounds to report
        std::memcpy(mem, &bounds.lo, sizeof(glm::vec3));
        std::memcpy(static_cast<char*>(mem) + sizeof(glm::vec3), &bounds.hi, sizeof(glm::vec3));
        return true;
    }
    return SceneObject::getProperty(name, type, mem, size, wait);
}

}  // namespace ripple::device
