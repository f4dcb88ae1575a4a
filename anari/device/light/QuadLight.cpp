// Light subtype "quad" (KHR_LIGHT_QUAD): a parallelogram (position + s edge1 + t edge2) emitting from
// its front (along edge1 x edge2), back or both sides. Its strength is "radiance" W/sr/m^2, else "power" W
// over the emitting sides, else "intensity" W/sr along the normal (radiance = intensity / area).
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"

#include "anari/device/scene/ArrayConversion.h"

#include <glm/gtc/constants.hpp>

#include <string>
#include <utility>

namespace ripple::device {
namespace {

class QuadLight final : public Light {
public:
    explicit QuadLight(DeviceState& state) : Light(state, "quad") {}

    void commit() override {
        forgetDependencies();
        light_ = core::Light{};
        light_.kind = core::Light::Kind::Quad;
        light_.color = pullColor();
        light_.position = get<glm::vec3>("position", glm::vec3(0.0f));
        light_.edge1 = get<glm::vec3>("edge1", glm::vec3(1.0f, 0.0f, 0.0f));
        light_.edge2 = get<glm::vec3>("edge2", glm::vec3(0.0f, 1.0f, 0.0f));
        if (reject(nonFiniteProblem("position", light_.position)) || reject(nonFiniteProblem("edge1", light_.edge1)) ||
            reject(nonFiniteProblem("edge2", light_.edge2)))
            return;
        const float area = glm::length(glm::cross(light_.edge1, light_.edge2));
        if (!(area > 0.0f) || !std::isfinite(area)) {
            invalidate("parameters 'edge1' and 'edge2' must span a non-zero, finite area");
            return;
        }

        const std::string side = getString("side", "front");
        if (side != "front" && side != "back" && side != "both")
            reportWarning("parameter 'side' has unknown value '" + side + "'; using 'front'");
        light_.twoSided = side == "both";
        // Core emits along cross(edge1, edge2): swapping the edges turns the quad around.
        if (side == "back") std::swap(light_.edge1, light_.edge2);

        const std::optional<float> radiance = pullAmount("radiance");
        const std::optional<float> power = pullAmount("power");
        const std::optional<float> intensity = pullAmount("intensity");
        // A Lambertian emitter of radiance L and area A emits pi L A watts per side and L A W/sr normally.
        const float sides = light_.twoSided ? 2.0f : 1.0f;
        if (radiance)
            light_.intensity = *radiance;
        else if (power)
            light_.intensity = *power / (glm::pi<float>() * area * sides);
        else
            light_.intensity = intensity.value_or(1.0f) / area;
    }
};

}  // namespace

Light* newQuadLight(DeviceState& state) {
    return new QuadLight(state);
}

}  // namespace ripple::device
