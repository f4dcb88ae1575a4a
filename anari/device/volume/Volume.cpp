// Volume "transferFunction1D": field, value range, colour and opacity (uniform or arrays), unitDistance.
#include "anari/device/volume/Volume.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <cmath>
#include <cstring>
#include <string>

namespace ripple::device {

void Volume::commit() {
    forgetDependencies();
    field_ = dynamic_cast<SpatialField*>(getObject("value", ANARI_SPATIAL_FIELD));
    if (!field_) {
        invalidate(has("value") ? "parameter 'value' is not a spatial field Ripple knows"
                                : "missing required parameter 'value' (a spatial field)");
        return;
    }
    useChild(field_);
    visible_ = get<bool>("visible", true);
    id_ = getOptional<uint32_t>("id");

    // valueRange: FLOAT32_BOX1 or FLOAT64_BOX1 (two numbers); an inverted range is taken in order. The same
    // two numbers as FLOAT32_VEC2 or FLOAT64_VEC2, which the SDK's own CTS and test scenes pass, read alike.
    valueRange_ = glm::vec2(0.0f, 1.0f);
    const ANARIDataType rangeType = parameterType("valueRange");
    if (const Parameter* p = findParameter("valueRange")) {
        const bool floats = rangeType == ANARI_FLOAT32_BOX1 || rangeType == ANARI_FLOAT32_VEC2;
        const bool doubles = rangeType == ANARI_FLOAT64_BOX1 || rangeType == ANARI_FLOAT64_VEC2;
        if (floats && p->bytes.size() >= 2 * sizeof(float)) {
            std::memcpy(&valueRange_, p->bytes.data(), 2 * sizeof(float));
        } else if (doubles && p->bytes.size() >= 2 * sizeof(double)) {
            double range[2];
            std::memcpy(range, p->bytes.data(), sizeof(range));
            valueRange_ = glm::vec2(float(range[0]), float(range[1]));
        } else {
            reportWarning(std::string("parameter 'valueRange' has type ") + ripple_anari::typeName(rangeType) +
                          ", expected FLOAT32_BOX1 or FLOAT64_BOX1; using [0, 1]");
        }
    }
    if (!std::isfinite(valueRange_.x) || !std::isfinite(valueRange_.y)) {
        invalidate("parameter 'valueRange' is not finite");
        return;
    }
    if (valueRange_.x > valueRange_.y) {
        reportWarning("parameter 'valueRange' is inverted; using [" + std::to_string(valueRange_.y) + ", " +
                      std::to_string(valueRange_.x) + "]");
        std::swap(valueRange_.x, valueRange_.y);
    }
    if (valueRange_.x == valueRange_.y)
        reportWarning("parameter 'valueRange' is empty: every value maps to the first colour and opacity");

    // color: uniform FLOAT32_VEC3/VEC4 or an ARRAY1D of colours (sRGB types decoded). Their alpha is the
    // opacity where no 'opacity' is given, as other ANARI devices and pynari's samples take it (1 for colours
    // without alpha).
    colors_.clear();
    std::vector<float> alphas;
    switch (parameterType("color")) {
        case ANARI_UNKNOWN: break;
        case ANARI_FLOAT32_VEC3: colors_ = {get<glm::vec3>("color", glm::vec3(1.0f))}; break;
        case ANARI_FLOAT32_VEC4: {
            const glm::vec4 color = get<glm::vec4>("color", glm::vec4(1.0f));
            colors_ = {glm::vec3(color)};
            alphas = {color.a};
            break;
        }
        default:
            if (Array* array = getArray("color")) {
                useArray(array);
                const std::optional<std::vector<glm::vec4>> values = readFloatVectors(*array, glm::vec4(0, 0, 0, 1));
                if (!values) {
                    invalidate(elementTypeProblem("color", array->elementType(), "colours (e.g. FLOAT32_VEC3)"));
                    return;
                }
                for (const glm::vec4& c : *values) {
                    colors_.emplace_back(c);
                    alphas.push_back(c.a);
                }
                if (colors_.empty()) reportWarning("parameter 'color' is an empty array; using white");
            } else {
                reportWarning("parameter 'color' must be FLOAT32_VEC3, FLOAT32_VEC4 or an ARRAY1D; using white");
            }
    }
    for (const glm::vec3& c : colors_)
        if (reject(nonFiniteProblem("color", c))) return;

    // opacity: uniform FLOAT32 or an ARRAY1D of FLOAT32.
    opacities_.clear();
    if (!has("opacity")) {
        opacities_ = alphas;
    } else if (parameterType("opacity") == ANARI_FLOAT32) {
        opacities_ = {get<float>("opacity", 1.0f)};
    } else if (Array* array = getArray("opacity")) {
        useArray(array);
        const std::optional<std::vector<glm::vec4>> values = readFloatVectors(*array);
        if (!values) {
            invalidate(elementTypeProblem("opacity", array->elementType(), "FLOAT32"));
            return;
        }
        for (const glm::vec4& o : *values) opacities_.push_back(o.x);
        if (opacities_.empty()) reportWarning("parameter 'opacity' is an empty array; using 1");
    } else {
        reportWarning("parameter 'opacity' must be FLOAT32 or an ARRAY1D; using 1");
    }
    for (float o : opacities_)
        if (reject(nonFiniteProblem("opacity", o))) return;

    unitDistance_ = get<float>("unitDistance", 1.0f);
    if (!(unitDistance_ > 0.0f) || !std::isfinite(unitDistance_)) {
        invalidate("parameter 'unitDistance' must be finite and positive, not " + std::to_string(unitDistance_));
        return;
    }
}

core::Volume Volume::volume() const {
    core::Volume v;
    if (!field_) return v;
    field_->describe(v);
    v.valueRange = valueRange_;
    v.colors = colors_;
    v.opacities = opacities_;
    v.unitDistance = unitDistance_;
    return v;
}

}  // namespace ripple::device
