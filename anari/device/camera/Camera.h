// ANARI camera: perspective, orthographic and omnidirectional become a core::Camera. When the application sets no
// "aspect", the frame's width / height is used. Perspective and orthographic cameras clip at "near" and "far".
#pragma once

#include "anari/device/object/Object.h"
#include "core/render/PathTracer.h"

#include <optional>

namespace ripple::device {

class Camera : public Object {
public:
    Camera(DeviceState& state, std::string subtype) : Object(state, ANARI_CAMERA, std::move(subtype)) {}

    // The committed camera for a frame of the given aspect (used when "aspect" is unset).
    core::Camera camera(float frameAspect) const;

protected:
    // For commit(): position, direction, up, imageRegion and aspect, which all subtypes share. False after
    // invalidate() when direction and up are degenerate.
    bool pullView(core::Camera::Kind kind);

    core::Camera camera_;
    std::optional<float> aspect_;
};

Camera* newPerspectiveCamera(DeviceState& state);
Camera* newOrthographicCamera(DeviceState& state);
Camera* newOmnidirectionalCamera(DeviceState& state);

}  // namespace ripple::device
