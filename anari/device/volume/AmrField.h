// ANARI spatial field "amr": a block-structured AMR hierarchy with the parameters anari-ospray gives it
// (reported as the vendor extension ANARI_RIPPLE_SPATIAL_FIELD_AMR until Khronos names one):
//   cellWidth     ARRAY1D of FLOAT32, per level, decreasing (level 0 usually 1)
//   block.bounds  ARRAY1D of INT32_BOX3: each block's cells, inclusive, in its level's index space
//   block.level   ARRAY1D of INT32 or UINT32
//   block.data    ARRAY1D of ARRAY3D: each block's cell values, dims equal to its bounds' extent
//   origin, spacing  FLOAT32_VEC3: cell (i, j, k) of level l starts at origin + spacing * cellWidth[l] * (i, j, k)
// Checked and packed at commit (core/scene/AmrGrid.h); a hierarchy Ripple cannot render makes the field
// invalid, naming the problem. The value at a point is the finest covering cell's.
#pragma once

#include "anari/device/volume/SpatialField.h"
#include "core/scene/AmrGrid.h"

#include <memory>

namespace ripple::device {

class AmrField final : public SpatialField {
public:
    explicit AmrField(DeviceState& state) : SpatialField(state, "amr") {}

    void commit() override;
    bvh::Aabb bounds() const override;
    void describe(core::Volume& volume) const override;

private:
    std::shared_ptr<const core::AmrGrid> grid_;
};

}  // namespace ripple::device
