// ANARI spatial field "unstructured" (KHR_SPATIAL_FIELD_UNSTRUCTURED): cells of VTK types 10 (tetrahedron),
// 12 (hexahedron), 13 (wedge) and 14 (pyramid) over "vertex.position", with values per vertex
// ("vertex.data") or per cell ("cell.data", piecewise constant); cell c's corners are
// index[cell.index[c] ..] in VTK's vertex order for cell.type[c]. Checked and packed for the kernels at
// commit (core/scene/UnstructuredGrid.h): a mesh Ripple cannot use makes the field invalid, naming the
// first problem; zero-volume cells are dropped and inverted ones kept, with a warning each.
#pragma once

#include "anari/device/volume/SpatialField.h"
#include "core/scene/UnstructuredGrid.h"

#include <memory>

namespace ripple::device {

class UnstructuredField final : public SpatialField {
public:
    explicit UnstructuredField(DeviceState& state) : SpatialField(state, "unstructured") {}

    void commit() override;
    bvh::Aabb bounds() const override;
    void describe(core::Volume& volume) const override;
    // The committed mesh as the kernels read it (iso-surfaces are found in it too); null when the field is
    // not valid.
    std::shared_ptr<const core::UnstructuredGrid> grid() const { return isValid() ? grid_ : nullptr; }

private:
    std::shared_ptr<const core::UnstructuredGrid> grid_;
};

}  // namespace ripple::device
