// ANARI spatial field "structuredRegular" (KHR_SPATIAL_FIELD_STRUCTURED_REGULAR): a 3D array of
// cell-vertex samples ("data": UFIXED8, FIXED16, UFIXED16 normalised as the spec says, FLOAT32, FLOAT64)
// at origin + index * spacing, filtered "linear" or "nearest". Volumes (Volume.h) read it.
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/bvh/Aabb.h"

#include <glm/glm.hpp>

#include <vector>

namespace ripple::device {

class SpatialField final : public SceneObject {
public:
    explicit SpatialField(DeviceState& state) : SceneObject(state, ANARI_SPATIAL_FIELD, "structuredRegular") {}

    void commit() override;

    glm::uvec3 dims() const { return dims_; }
    const std::vector<float>& values() const { return values_; }  // x fastest
    glm::vec3 origin() const { return origin_; }
    glm::vec3 spacing() const { return spacing_; }
    bool linearFilter() const { return linearFilter_; }
    // Object-space box the samples span; empty when the field is not valid.
    bvh::Aabb bounds() const;

private:
    glm::uvec3 dims_{0};
    std::vector<float> values_;
    glm::vec3 origin_{0.0f};
    glm::vec3 spacing_{1.0f};
    bool linearFilter_ = true;
};

}  // namespace ripple::device
