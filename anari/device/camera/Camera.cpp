// The view parameters all camera subtypes share (see Camera.h).
#include "anari/device/camera/Camera.h"

#include "anari/device/scene/ArrayConversion.h"

#include <cmath>

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

    if (!allFinite(camera_.position) || !allFinite(direction) || !allFinite(up) ||
        glm::length(glm::cross(direction, up)) == 0.0f) {
        invalidate(
            "parameters 'position', 'direction' and 'up' must be finite, with 'direction' and 'up' "
            "non-zero and not parallel");
        return false;
    }
    camera_.direction = glm::normalize(direction);
    camera_.up = glm::normalize(up);
    if (!allFinite(camera_.imageRegion) || !(region.upper.x > region.lower.x) || !(region.upper.y > region.lower.y)) {
        reportWarning("parameter 'imageRegion' must be a non-empty finite box; using (0, 0)-(1, 1)");
        camera_.imageRegion = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    }
    return true;
}

}  // namespace ripple::device
