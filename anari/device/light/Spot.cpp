// Light subtypes "spot" (KHR_LIGHT_SPOT) and "ring" (KHR_LIGHT_RING): light along "direction" within
// openingAngle / 2 of it, fading over the last falloffAngle. A ring is an emitting annulus (radius,
// innerRadius) with that profile; its "radiance" (W/sr/m^2) or else "intensity" (W/sr along the axis,
// spread over the annulus) or "power" sets its brightness.
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"

#include "anari/device/scene/ArrayConversion.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>

namespace ripple::device {
namespace {

class SpotLight final : public Light {
public:
    SpotLight(DeviceState& state, bool ring) : Light(state, ring ? "ring" : "spot"), ring_(ring) {}

    void commit() override {
        forgetDependencies();
        light_ = core::Light{};
        light_.kind = ring_ ? core::Light::Kind::Ring : core::Light::Kind::Spot;
        light_.color = pullColor();
        light_.position = get<glm::vec3>("position", glm::vec3(0.0f));
        light_.direction = get<glm::vec3>("direction", glm::vec3(0.0f, 0.0f, -1.0f));
        const float openingAngle = get<float>("openingAngle", glm::pi<float>());
        const float falloffAngle = get<float>("falloffAngle", 0.1f);
        // Checked before the clamps below, which would pass a NaN through.
        if (reject(nonFiniteProblem("position", light_.position)) ||
            reject(nonFiniteProblem("direction", light_.direction)) ||
            reject(nonFiniteProblem("openingAngle", openingAngle)) ||
            reject(nonFiniteProblem("falloffAngle", falloffAngle)))
            return;
        light_.openingAngle = std::clamp(openingAngle, 0.0f, glm::two_pi<float>());
        light_.falloffAngle = std::max(falloffAngle, 0.0f);
        // Solid angle of the cone, for "power".
        const float cone = glm::two_pi<float>() * (1.0f - std::cos(0.5f * std::min(light_.openingAngle, glm::two_pi<float>())));
        const std::optional<float> intensity = pullAmount("intensity");
        const std::optional<float> power = pullAmount("power");
        float axisIntensity = intensity ? *intensity : power && cone > 0.0f ? *power / cone : 1.0f;
        light_.intensity = axisIntensity;
        if (!ring_) return;
        const float radius = get<float>("radius", 0.0f);
        const float innerRadius = get<float>("innerRadius", 0.0f);
        if (reject(nonFiniteProblem("radius", radius)) || reject(nonFiniteProblem("innerRadius", innerRadius))) return;
        light_.radius = std::max(radius, 0.0f);
        light_.innerRadius = std::clamp(innerRadius, 0.0f, light_.radius);
        const float area = glm::pi<float>() * (light_.radius * light_.radius - light_.innerRadius * light_.innerRadius);
        const std::optional<float> radiance = pullAmount("radiance");
        // An area emitter of radiance L sends L * area along its axis.
        if (area > 0.0f) light_.intensity = radiance ? *radiance : axisIntensity / area;
        (void)findParameter("c0");  // photometric orientation: no intensityDistribution support, nothing to orient
    }

private:
    bool ring_;
};

}  // namespace

Light* newSpotLight(DeviceState& state) { return new SpotLight(state, false); }
Light* newRingLight(DeviceState& state) { return new SpotLight(state, true); }

}  // namespace ripple::device
