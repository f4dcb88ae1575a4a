// ANARI world: everything a frame renders: instances, and surfaces, volumes and lights placed without one.
// Its "bounds" property is computed on the host from the committed geometry.
#pragma once

#include "anari/device/instance/Instance.h"
#include "anari/device/volume/Volume.h"

#include <vector>

namespace ripple::device {

class World final : public SceneObject {
public:
    explicit World(DeviceState& state);

    void commit() override;
    bool getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait) override;

    const std::vector<Instance*>& instances() const { return instances_; }
    const std::vector<Surface*>& surfaces() const { return surfaces_; }
    const std::vector<Light*>& lights() const { return lights_; }
    const std::vector<Volume*>& volumes() const { return volumes_; }
    // Data-parallel ANARI: the N-th world created on each rank is the same world.
    uint64_t globalIndex() const { return globalIndex_; }

private:
    std::vector<Instance*> instances_;  // kept alive by useChild()
    std::vector<Surface*> surfaces_;
    std::vector<Light*> lights_;
    std::vector<Volume*> volumes_;
    uint64_t globalIndex_ = 0;
};

}  // namespace ripple::device
