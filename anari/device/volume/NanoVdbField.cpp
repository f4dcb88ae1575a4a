// Spatial field "nanovdb": the grid buffer checked and prepared by core (NanoVdbField.h).
#include "anari/device/volume/NanoVdbField.h"

#include "anari/device/object/ArrayChecks.h"

#include <stdexcept>
#include <string>

namespace ripple::device {

void NanoVdbField::commit() {
    forgetDependencies();
    grid_.reset();
    Array* data = getArray("data");
    if (!data) {
        invalidate(has("data") ? "parameter 'data' must be an ARRAY1D of UINT8 (a NanoVDB grid buffer)"
                               : "missing required parameter 'data' (a NanoVDB grid buffer)");
        return;
    }
    useArray(data);
    if (data->elementType() != ANARI_UINT8 && data->elementType() != ANARI_INT8) {
        invalidate(elementTypeProblem("data", data->elementType(), "UINT8 (the bytes of a NanoVDB grid buffer)"));
        return;
    }
    try {
        grid_ = core::prepareNanoVdbGrid(std::span<const uint8_t>(static_cast<const uint8_t*>(data->data()), data->size()));
    } catch (const std::invalid_argument& e) {
        invalidate(std::string("parameter 'data' is not a NanoVDB grid Ripple can render: ") + e.what());
        return;
    }
    linearFilter_ = linearFilterParameter();
}

bvh::Aabb NanoVdbField::bounds() const {
    bvh::Aabb box;
    if (!isValid() || !grid_) return box;
    const glm::dvec3 lo(grid_->base), hi = lo + glm::dvec3(grid_->extent);
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0);
        box.extend(glm::vec3(grid_->indexToObject * corner));
    }
    return box;
}

void NanoVdbField::describe(core::Volume& v) const {
    v.nanovdb = grid_;
    v.linearFilter = linearFilter_;
    v.voxelIdentity = {reinterpret_cast<uintptr_t>(this), lastCommitted()};
}

}  // namespace ripple::device
