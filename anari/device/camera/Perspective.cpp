// Camera subtype "perspective" (KHR_CAMERA_PERSPECTIVE): a pinhole with vertical field of view "fovy"
// (radians, default pi/3). "near" and "far" clipping are not supported yet.
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
    }
};

}  // namespace

Camera* newPerspectiveCamera(DeviceState& state) {
    return new PerspectiveCamera(state);
}

}  // namespace ripple::device
