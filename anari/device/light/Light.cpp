// Parameter pulling shared by the light subtypes (see Light.h).
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"

#include <string>

namespace ripple::device {

glm::vec3 Light::pullColor() {
    const glm::vec3 color = get<glm::vec3>("color", glm::vec3(1.0f));
    if (reject(nonFiniteProblem("color", color))) return glm::vec3(1.0f);
    if (glm::any(glm::lessThan(color, glm::vec3(0.0f)))) {
        invalidate("parameter 'color' is negative");
        return glm::vec3(1.0f);
    }
    return color;
}

std::optional<float> Light::pullAmount(std::string_view name) {
    const std::optional<float> amount = getOptional<float>(name);
    if (!amount) return std::nullopt;
    if (reject(nonFiniteProblem(name, *amount))) return std::nullopt;
    if (*amount < 0.0f) {
        invalidate("parameter '" + std::string(name) + "' is negative (" + std::to_string(*amount) + ")");
        return std::nullopt;
    }
    return amount;
}

}  // namespace ripple::device
