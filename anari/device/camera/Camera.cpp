// The view parameters all camera subtypes share (see Camera.h).
#include "anari/device/camera/Camera.h"

#include "anari/device/scene/ArrayConversion.h"

#include <cmath>
#include <limits>
#include <string>

namespace ripple::device {

// ANARI_FLOAT32_BOX2: the (lower, upper) corners of imageRegion.
struct Box2 {
    glm::vec2 lower;
    glm::vec2 upper;
};
template <>
constexpr ANARIDataType anariTypeOf<Box2>() {
    return ANARI_FLOAT32_BOX2;
}

namespace {

// v / |v|, scaled first by its largest component so that neither a tiny nor a huge vector (1e-30, 1e30:
// their squared length leaves float's range) is taken for zero or normalised to zero.
std::optional<glm::vec3> unitVector(glm::vec3 v) {
    if (!allFinite(v)) return std::nullopt;
    const float largest = glm::max(glm::abs(v.x), glm::max(glm::abs(v.y), glm::abs(v.z)));
    if (largest == 0.0f) return std::nullopt;
    return glm::normalize(v / largest);
}

}  // namespace

core::Camera Camera::camera(float frameAspect) const {
    core::Camera camera = camera_;
    camera.aspect = aspect_.value_or(frameAspect);
    return camera;
}

bool Camera::pullView(core::Camera::Kind kind) {
    camera_ = core::Camera{};
    camera_.kind = kind;
    camera_.position = get<glm::vec3>("position", glm::vec3(0.0f));
    const glm::vec3 direction = get<glm::vec3>("direction", glm::vec3(0.0f, 0.0f, -1.0f));
    const glm::vec3 up = get<glm::vec3>("up", glm::vec3(0.0f, 1.0f, 0.0f));
    const Box2 region = get<Box2>("imageRegion", Box2{glm::vec2(0.0f), glm::vec2(1.0f)});
    camera_.imageRegion = glm::vec4(region.lower, region.upper);
    aspect_ = getOptional<float>("aspect");
    if (aspect_ && !(std::isfinite(*aspect_) && *aspect_ > 0.0f)) {
        reportWarning("parameter 'aspect' must be finite and positive; using the frame's aspect");
        aspect_.reset();
    }

    if (!allFinite(camera_.position)) {
        invalidate("parameter 'position' must be finite");
        return false;
    }
    const std::optional<glm::vec3> unitDirection = unitVector(direction);
    const std::optional<glm::vec3> unitUp = unitVector(up);
    if (!unitDirection || !unitUp) {
        invalidate(std::string("parameter '") + (unitDirection ? "up" : "direction") +
                   "' must be a finite, non-zero vector");
        return false;
    }
    if (glm::length(glm::cross(*unitDirection, *unitUp)) == 0.0f) {
        invalidate("parameters 'direction' and 'up' are parallel; 'up' must point away from the view direction");
        return false;
    }
    camera_.direction = *unitDirection;
    camera_.up = *unitUp;
    if (!allFinite(camera_.imageRegion) || !(region.upper.x > region.lower.x) || !(region.upper.y > region.lower.y)) {
        reportWarning("parameter 'imageRegion' must be a non-empty finite box; using (0, 0)-(1, 1)");
        camera_.imageRegion = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    }
    if (kind != core::Camera::Kind::Omnidirectional) {  // clip planes: perspective and orthographic only
        const float nearClip = get<float>("near", 0.0f);
        const float farClip = get<float>("far", std::numeric_limits<float>::infinity());
        if (!(std::isfinite(nearClip) && nearClip >= 0.0f)) {
            reportWarning("parameter 'near' must be finite and not negative; no near clipping");
        } else {
            camera_.nearClip = nearClip;
        }
        if (!(farClip > camera_.nearClip)) {  // NaN included
            reportWarning("parameter 'far' must be greater than 'near'; no far clipping");
        } else {
            camera_.farClip = farClip;
        }
    }
    return true;
}

}  // namespace ripple::device
