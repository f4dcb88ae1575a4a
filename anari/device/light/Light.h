// ANARI light: directional, point, quad, spot, ring and hdri lights become a core::Light (in the space of the group or
// world that holds them; SceneSync applies instance transforms).
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/scene/SceneDescription.h"

#include <optional>

namespace ripple::device {

class Light : public SceneObject {
public:
    Light(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_LIGHT, std::move(subtype)) {}
    const core::Light& light() const { return light_; }
    // The image an hdri light emits (its texture index is set by SceneSync); nullptr for other lights.
    virtual const core::Texture* image() const { return nullptr; }

protected:
    // For commit(): "color" (default white); a non-finite or negative one invalidates the light.
    glm::vec3 pullColor();
    // A non-negative finite float parameter, or nullopt when unset or bad (bad invalidates the light).
    std::optional<float> pullAmount(std::string_view name);

    core::Light light_;
};

Light* newDirectionalLight(DeviceState& state);
Light* newPointLight(DeviceState& state);
Light* newQuadLight(DeviceState& state);
Light* newSpotLight(DeviceState& state);
Light* newRingLight(DeviceState& state);
Light* newHdriLight(DeviceState& state);

}  // namespace ripple::device
