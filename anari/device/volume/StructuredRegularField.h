// ANARI spatial field "structuredRegular" (KHR_SPATIAL_FIELD_STRUCTURED_REGULAR): a 3D array of
// cell-vertex samples ("data": UFIXED8, FIXED16, UFIXED16 normalised as the spec says, FLOAT32, FLOAT64)
// at origin + index * spacing, filtered "linear" or "nearest". Volumes (Volume.h) read it.
#pragma once

#include "anari/device/volume/SpatialField.h"

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace ripple::device {

class StructuredRegularField final : public SpatialField {
public:
    explicit StructuredRegularField(DeviceState& state) : SpatialField(state, "structuredRegular") {}

    void commit() override;

    glm::uvec3 dims() const { return dims_; }
    // x fastest; empty when the field is not valid. A commit makes a new array (a scene being built or
    // rendered keeps the one it took: sharedValues).
    const std::vector<float>& values() const { return values_ ? *values_ : kNoValues; }
    std::shared_ptr<const std::vector<float>> sharedValues() const { return values_; }
    glm::vec3 origin() const { return origin_; }
    glm::vec3 spacing() const { return spacing_; }
    bool linearFilter() const { return linearFilter_; }
    bvh::Aabb bounds() const override;
    void describe(core::Volume& volume) const override;

private:
    glm::uvec3 dims_{0};
    static inline const std::vector<float> kNoValues;
    std::shared_ptr<const std::vector<float>> values_;
    glm::vec3 origin_{0.0f};
    glm::vec3 spacing_{1.0f};
    bool linearFilter_ = true;
};

}  // namespace ripple::device
