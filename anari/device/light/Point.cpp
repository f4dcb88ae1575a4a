// Light subtype "point" (KHR_LIGHT_POINT): an isotropic point light of "intensity" W/sr, or of "power" W
// (intensity = power / 4 pi) when that is given instead. "radius" (sphere light) is not supported yet.
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"


#include <glm/gtc/constants.hpp>

namespace ripple::device {
namespace {

class PointLight final : public Light {
public:
    explicit PointLight(DeviceState& state) : Light(state, "point") {}

    void commit() override {
        forgetDependencies();
        light_ = core::Light{};
        light_.kind = core::Light::Kind::Point;
        light_.color = pullColor();
        const std::optional<float> intensity = pullAmount("intensity");
        const std::optional<float> power = pullAmount("power");
        light_.intensity = intensity ? *intensity : power ? *power / (4.0f * glm::pi<float>()) : 1.0f;
        light_.position = get<glm::vec3>("position", glm::vec3(0.0f));
        reject(nonFiniteProblem("position", light_.position));
    }
};

}  // namespace

Light* newPointLight(DeviceState& state) {
    return new PointLight(state);
}

}  // namespace ripple::device
