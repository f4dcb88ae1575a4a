// Spatial field "structuredRegular": the voxels converted to float32 once, at commit.
#include "anari/device/volume/SpatialField.h"

#include "anari/device/object/ArrayChecks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace ripple::device {
namespace {

// The array's elements as floats, normalised as the spec says for the fixed-point types (UFIXED to
// [0, 1], FIXED16 to [-1, 1]); false for an element type the field does not take.
template <class T>
void convert(const Array& array, std::vector<float>& out, double scale, double lowest) {
    const std::span<const T> in = array.as<T>();
    out.resize(in.size());
    for (size_t i = 0; i < in.size(); ++i) out[i] = float(std::max(double(in[i]) * scale, lowest));
}

bool convertVoxels(const Array& array, std::vector<float>& out) {
    const double none = -std::numeric_limits<double>::max();
    switch (array.elementType()) {
        case ANARI_UFIXED8: convert<uint8_t>(array, out, 1.0 / 255.0, none); return true;
        case ANARI_UFIXED16: convert<uint16_t>(array, out, 1.0 / 65535.0, none); return true;
        case ANARI_FIXED16: convert<int16_t>(array, out, 1.0 / 32767.0, -1.0); return true;
        case ANARI_FLOAT32: convert<float>(array, out, 1.0, none); return true;
        case ANARI_FLOAT64: convert<double>(array, out, 1.0, none); return true;
        default: return false;
    }
}

}  // namespace

void SpatialField::commit() {
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
    std::vector<float> values;
    if (!convertVoxels(*data, values)) {
        invalidate(std::string("parameter 'data' has element type ") + ripple_anari::typeName(data->elementType()) +
                   "; a structuredRegular field takes UFIXED8, FIXED16, UFIXED16, FLOAT32 or FLOAT64");
        return;
    }
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
    const std::string filter = getString("filter", "linear");
    if (filter != "linear" && filter != "nearest")
        reportWarning("parameter 'filter' has unknown value '" + filter + "'; using 'linear'");
    linearFilter_ = filter != "nearest";
}

bvh::Aabb SpatialField::bounds() const {
    bvh::Aabb box;
    if (!isValid() || values().empty()) return box;
    box.extend(origin_);
    box.extend(origin_ + glm::vec3(dims_ - 1u) * spacing_);
    return box;
}

}  // namespace ripple::device
