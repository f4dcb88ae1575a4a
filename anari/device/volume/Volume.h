// ANARI volume "transferFunction1D" (KHR_VOLUME_TRANSFER_FUNCTION1D): a spatial field ("value") mapped
// through colour and opacity over "valueRange", with "unitDistance" (opacity o means transmittance 1 - o
// over that distance). Path-traced as a scattering medium whose albedo is the colour (core::Volume).
#pragma once

#include "anari/device/volume/SpatialField.h"
#include "core/scene/SceneDescription.h"

namespace ripple::device {

class Volume final : public SceneObject {
public:
    explicit Volume(DeviceState& state) : SceneObject(state, ANARI_VOLUME, "transferFunction1D") {}

    void commit() override;
    // Valid, visible and with a valid field.
    bool renderable() const { return isValid() && visible_ && field_ && field_->isValid(); }
    // The committed volume in object space (transform identity); the field's voxels are copied in.
    core::Volume volume() const;
    // "id" (KHR_FRAME_CHANNEL_OBJECT_ID): what the objectId channel shows where the volume scatters.
    std::optional<uint32_t> id() const { return id_; }
    bvh::Aabb bounds() const { return field_ ? field_->bounds() : bvh::Aabb{}; }

private:
    SpatialField* field_ = nullptr;  // kept alive by useChild()
    glm::vec2 valueRange_{0.0f, 1.0f};
    std::vector<glm::vec3> colors_;
    std::vector<float> opacities_;
    float unitDistance_ = 1.0f;
    bool visible_ = true;
    std::optional<uint32_t> id_;
};

}  // namespace ripple::device
