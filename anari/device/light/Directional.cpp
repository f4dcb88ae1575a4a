// Light subtype "directional" (KHR_LIGHT_DIRECTIONAL): parallel light travelling along "direction" with
// "irradiance" W/m^2 on a surface facing it. "angularDiameter" (soft sun) is not supported yet.
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"


namespace ripple::device {
namespace {

class DirectionalLight final : public Light {
public:
    explicit DirectionalLight(DeviceState& state) : Light(state, "directional") {}

    void commit() override {
        forgetDependencies();
        light_ = core::Light{};
        light_.kind = core::Light::Kind::Directional;
        light_.color = pullColor();
        light_.intensity = pullAmount("irradiance").value_or(1.0f);
        const glm::vec3 direction = get<glm::vec3>("direction", glm::vec3(0.0f, 0.0f, -1.0f));
        if (reject(nonFiniteProblem("direction", direction))) return;
        if (!(glm::length(direction) > 0.0f)) {
            invalidate("parameter 'direction' must be a non-zero vector");
            return;
        }
        light_.direction = glm::normalize(direction);
    }
};

}  // namespace

Light* newDirectionalLight(DeviceState& state) {
    return new DirectionalLight(state);
}

}  // namespace ripple::device
