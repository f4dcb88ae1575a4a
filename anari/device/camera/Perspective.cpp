// Camera subtype "perspective" (KHR_CAMERA_PERSPECTIVE): a pinhole with vertical field of view "fovy"
// (radians, default pi/3), with depth of field (KHR_CAMERA_DEPTH_OF_FIELD) from "apertureRadius" (default
// 0: a pinhole) and "focusDistance" (default 1); "near" and "far" clip planes (Camera.cpp).
#include "anari/device/camera/Camera.h"

#include <cmath>

namespace ripple::device {
namespace {

class PerspectiveCamera final : public Camera {
public:
    explicit PerspectiveCamera(DeviceState& state) : Camera(state, "perspective") {}

    void commit() override {
        if (!pullView(core::Camera::Kind::Perspective)) return;
        const float fovy = get<float>("fovy", 1.0471975512f);
        if (std::isfinite(fovy) && fovy > 0.0f && fovy < 3.14159f) {
            camera_.fovy = fovy;
        } else {
            reportWarning("parameter 'fovy' must be between 0 and pi radians; using pi/3");
            camera_.fovy = 1.0471975512f;
        }
        const float aperture = get<float>("apertureRadius", 0.0f);
        const float focus = get<float>("focusDistance", 1.0f);
        if (!(std::isfinite(aperture) && aperture >= 0.0f)) {
            reportWarning("parameter 'apertureRadius' must be finite and not negative; using 0 (no depth of field)");
        } else if (!(std::isfinite(focus) && focus > 0.0f)) {
            reportWarning("parameter 'focusDistance' must be finite and positive; depth of field disabled");
        } else {
            camera_.apertureRadius = aperture;
            camera_.focusDistance = focus;
        }
    }
};

}  // namespace

Camera* newPerspectiveCamera(DeviceState& state) {
    return new PerspectiveCamera(state);
}

}  // namespace ripple::device
