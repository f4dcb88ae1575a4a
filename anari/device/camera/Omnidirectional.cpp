// Camera subtype "omnidirectional" (KHR_CAMERA_OMNIDIRECTIONAL): the whole sphere of directions around
// "position" in the "equirectangular" layout (the only one the spec defines): longitude across the width,
// latitude up the height, the image centre looking along "direction" with "up" towards the top.
#include "anari/device/camera/Camera.h"

namespace ripple::device {
namespace {

class OmnidirectionalCamera final : public Camera {
public:
    explicit OmnidirectionalCamera(DeviceState& state) : Camera(state, "omnidirectional") {}

    void commit() override {
        if (!pullView(core::Camera::Kind::Omnidirectional)) return;
        const std::string layout = getString("layout", "equirectangular");
        if (layout != "equirectangular")
            reportWarning("parameter 'layout' has unknown value '" + layout + "'; using 'equirectangular'");
    }
};

}  // namespace

Camera* newOmnidirectionalCamera(DeviceState& state) {
    return new OmnidirectionalCamera(state);
}

}  // namespace ripple::device
