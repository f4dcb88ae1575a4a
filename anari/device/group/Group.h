// ANARI group: the surfaces and lights that instances place together.
#pragma once

#include "anari/device/light/Light.h"
#include "anari/device/surface/Surface.h"

#include <vector>

namespace ripple::device {

class Group final : public SceneObject {
public:
    explicit Group(DeviceState& state) : SceneObject(state, ANARI_GROUP, "") {}

    void commit() override;
    const std::vector<Surface*>& surfaces() const { return surfaces_; }
    const std::vector<Light*>& lights() const { return lights_; }

private:
    std::vector<Surface*> surfaces_;  // kept alive by useChild()
    std::vector<Light*> lights_;
};

}  // namespace ripple::device
