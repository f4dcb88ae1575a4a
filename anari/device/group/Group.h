// ANARI group: the surfaces, volumes and lights that instances place together.
#pragma once

#include "anari/device/light/Light.h"
#include "anari/device/surface/Surface.h"
#include "anari/device/volume/Volume.h"

#include <vector>

namespace ripple::device {

class Group final : public SceneObject {
public:
    explicit Group(DeviceState& state) : SceneObject(state, ANARI_GROUP, "") {}

    void commit() override;
    const std::vector<Surface*>& surfaces() const { return surfaces_; }
    const std::vector<Light*>& lights() const { return lights_; }
    const std::vector<Volume*>& volumes() const { return volumes_; }

private:
    std::vector<Surface*> surfaces_;  // kept alive by useChild()
    std::vector<Light*> lights_;
    std::vector<Volume*> volumes_;
};

}  // namespace ripple::device
