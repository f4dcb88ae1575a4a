// Parameter pulling shared by the light subtypes (see Light.h).
#include "anari/device/light/Light.h"

#include "anari/device/scene/ArrayConversion.h"

#include <string>

namespace ripple::device {

glm::vec3 Light::pullColor() {
    const glm::vec3 color = get<glm::vec3>("color", glm::vec3(1.0f));
    if (allFinite(color) && glm::all(glm::greaterThanEqual(color, glm::vec3(0.0f)))) return color;
    reportWarning("parameter 'color' must be finite and not negative; using white");
    return glm::vec3(1.0f);
}

std::optional<float> Light::pullAmount(std::string_view name) {
    const std::optional<float> amount = getOptional<float>(name);
    if (!amount) return std::nullopt;
    if (std::isfinite(*amount) && *amount >= 0.0f) return amount;
    reportWarning("parameter '" + std::string(name) + "' must be finite and not negative; ignored");
    return std::nullopt;
}

}  // namespace ripple::device
