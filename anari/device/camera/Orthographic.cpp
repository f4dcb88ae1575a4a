// Camera subtype "orthographic" (KHR_CAMERA_ORTHOGRAPHIC): parallel rays along "direction" from an image
// plane "height" world units tall (width = height * aspect), centred on "position".
#include "anari/device/camera/Camera.h"

#include <cmath>

namespace ripple::device {
namespace {

class OrthographicCamera final : public Camera {
public:
    explicit OrthographicCamera(DeviceState& state) : Camera(state, "orthographic") {}

    void commit() override {
        if (!pullView(core::Camera::Kind::Orthographic)) return;
        const float height = get<float>("height", 1.0f);
        if (std::isfinite(height) && height > 0.0f) {
            camera_.height = height;
        } else {
            reportWarning("parameter 'height' must be finite and positive; using 1");
            camera_.height = 1.0f;
        }
    }
};

}  // namespace

Camera* newOrthographicCamera(DeviceState& state) {
    return new OrthographicCamera(state);
}

}  // namespace ripple::device
