// Material subtype "matte" (KHR_MATERIAL_MATTE): a Lambertian surface of colour "color" (default 0.8).
#include "anari/device/material/Material.h"

#include <algorithm>

namespace ripple::device {
namespace {

class MatteMaterial final : public Material {
public:
    explicit MatteMaterial(DeviceState& state) : Material(state, "matte") {}

    void commit() override {
        reset(core::Material::Kind::Matte, glm::vec3(0.8f));
        pullBaseColor("color");
        material_.opacity = std::clamp(pullFactor("opacity", 1.0f, TextureSlot::Opacity), 0.0f, 1.0f);
        pullAlphaMode();
    }
};

}  // namespace

Material* newMatteMaterial(DeviceState& state) {
    return new MatteMaterial(state);
}

}  // namespace ripple::device
