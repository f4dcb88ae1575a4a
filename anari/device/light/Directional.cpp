// Light subtype "directional" (KHR_LIGHT_DIRECTIONAL): parallel light travelling along "direction" with
// "irradiance" W/m^2 on a surface facing it. "angularDiameter" (radians, 0 to pi) gives the light a disc of
// uniform radiance, a sun that BSDF-sampled rays can hit; 0, the default, is a delta light.
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"

#include <glm/gtc/constants.hpp>

#include <string>


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
        const float angularDiameter = get<float>("angularDiameter", 0.0f);
        if (reject(nonFiniteProblem("angularDiameter", angularDiameter))) return;
        if (!(angularDiameter >= 0.0f && angularDiameter <= glm::pi<float>())) {
            invalidate("parameter 'angularDiameter' must be in [0, pi] radians, got " + std::to_string(angularDiameter));
            return;
        }
        light_.angularDiameter = angularDiameter;
    }
};

}  // namespace

Light* newDirectionalLight(DeviceState& state) {
    return new DirectionalLight(state);
}

}  // namespace ripple::device
