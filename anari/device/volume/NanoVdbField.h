// ANARI spatial field "nanovdb" (KHR_SPATIAL_FIELD_NANOVDB): "data", an ARRAY1D of UINT8 holding a NanoVDB
// float grid buffer, sampled "nearest" or "linear" (default) in the grid's own index space and placed in
// object space by the grid's map. Checked at commit (core/scene/NanoVdbGrid.h): a buffer Ripple cannot read
// makes the field invalid, naming the problem, and no kernel ever reads it.
#pragma once

#include "anari/device/volume/SpatialField.h"
#include "core/scene/NanoVdbGrid.h"

#include <memory>

namespace ripple::device {

class NanoVdbField final : public SpatialField {
public:
    explicit NanoVdbField(DeviceState& state) : SpatialField(state, "nanovdb") {}

    void commit() override;
    bvh::Aabb bounds() const override;
    void describe(core::Volume& volume) const override;

private:
    std::shared_ptr<const core::NanoVdbGrid> grid_;
    bool linearFilter_ = true;
};

}  // namespace ripple::device
