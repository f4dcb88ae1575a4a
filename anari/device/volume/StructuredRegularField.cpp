// Spatial field "structuredRegular": the voxels converted to float32 once, at commit.
#include "anari/device/volume/StructuredRegularField.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace ripple::device {
void StructuredRegularField::commit() {
    forgetDependencies();
    values_.reset();
    dims_ = glm::uvec3(0);
    Array* data = getArray("data", ANARI_ARRAY3D);
    if (!data) {
        invalidate(has("data") ? "parameter 'data' must be an ARRAY3D" : "missing required parameter 'data'");
        return;
    }
    useArray(data);
    const glm::uvec3 dims(uint32_t(data->dim(0)), uint32_t(data->dim(1)), uint32_t(data->dim(2)));
    if (dims.x == 0 || dims.y == 0 || dims.z == 0) {
        invalidate("parameter 'data' is empty (" + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                   std::to_string(dims.z) + ")");
        return;
    }
    std::optional<std::vector<float>> converted = readScalars(*data);
    if (!converted) {
        invalidate(std::string("parameter 'data' has element type ") + ripple_anari::typeName(data->elementType()) +
                   "; a structuredRegular field takes UFIXED8, FIXED16, UFIXED16, FLOAT32 or FLOAT64");
        return;
    }
    std::vector<float>& values = *converted;
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i])) {
            invalidate("parameter 'data' element " + std::to_string(i) + " is not finite");
            return;
        }
    values_ = std::make_shared<const std::vector<float>>(std::move(values));
    dims_ = dims;
    origin_ = get<glm::vec3>("origin", glm::vec3(0.0f));
    spacing_ = get<glm::vec3>("spacing", glm::vec3(1.0f));
    if (reject(nonFiniteProblem("origin", origin_)) || reject(nonFiniteProblem("spacing", spacing_))) return;
    if (!glm::all(glm::greaterThan(spacing_, glm::vec3(0.0f)))) {
        invalidate("parameter 'spacing' must be positive on every axis");
        return;
    }
    linearFilter_ = linearFilterParameter();
}

bvh::Aabb StructuredRegularField::bounds() const {
    bvh::Aabb box;
    if (!isValid() || values().empty()) return box;
    box.extend(origin_);
    box.extend(origin_ + glm::vec3(dims_ - 1u) * spacing_);
    return box;
}

void StructuredRegularField::describe(core::Volume& v) const {
    v.dims = dims_;
    v.values = values_;
    // The voxels change only when the field is committed: a later scene reuses their device buffer.
    v.voxelIdentity = {reinterpret_cast<uintptr_t>(this), lastCommitted()};
    v.origin = origin_;
    v.spacing = spacing_;
    v.linearFilter = linearFilter_;
}

}  // namespace ripple::device
