// Material subtype "physicallyBased" (KHR_MATERIAL_PHYSICALLY_BASED): the glTF metallic-roughness model.
// baseColor, opacity (alphaMode, alphaCutoff), metallic, roughness, emissive, ior, specular, transmission,
// clearcoat and clearcoatRoughness are used; sheen, iridescence, thickness and attenuation are not yet,
// and are reported as unused parameters when set.
#include "anari/device/material/Material.h"
#include "anari/device/scene/ArrayConversion.h"

#include <algorithm>

namespace ripple::device {
namespace {

class PhysicallyBasedMaterial final : public Material {
public:
    explicit PhysicallyBasedMaterial(DeviceState& state) : Material(state, "physicallyBased") {}

    void commit() override {
        reset(core::Material::Kind::PhysicallyBased, glm::vec3(1.0f));
        pullBaseColor("baseColor");
        material_.opacity = std::clamp(pullFactor("opacity", 1.0f), 0.0f, 1.0f);
        material_.metallic = std::clamp(pullFactor("metallic", 1.0f), 0.0f, 1.0f);
        material_.roughness = std::clamp(pullFactor("roughness", 1.0f), 0.0f, 1.0f);
        material_.ior = std::max(pullFactor("ior", 1.5f), 1.0f);
        // Ripple follows glTF's KHR_materials_specular, where 1 keeps the ior's reflectance (ANARI's table
        // lists 0, which would remove dielectric reflection from every default material).
        material_.specular = std::clamp(pullFactor("specular", 1.0f), 0.0f, 1.0f);
        material_.transmission = std::clamp(pullFactor("transmission", 0.0f), 0.0f, 1.0f);
        material_.clearcoat = std::clamp(pullFactor("clearcoat", 0.0f), 0.0f, 1.0f);
        material_.clearcoatRoughness = std::clamp(pullFactor("clearcoatRoughness", 0.0f), 0.0f, 1.0f);
        pullEmissive();
        pullAlphaMode();
    }

private:
    void pullEmissive() {
        const ANARIDataType type = parameterType("emissive");
        if (type == ANARI_UNKNOWN) return;
        if (type != ANARI_FLOAT32_VEC3) {
            (void)findParameter("emissive");
            reportWarning("parameter 'emissive' as " + std::string(ripple_anari::typeName(type)) +
                          " is not supported yet (FLOAT32_VEC3 only); no emission");
            return;
        }
        const glm::vec3 emissive = get<glm::vec3>("emissive", glm::vec3(0.0f));
        if (allFinite(emissive) && glm::all(glm::greaterThanEqual(emissive, glm::vec3(0.0f))))
            material_.emissive = emissive;
        else
            reportWarning("parameter 'emissive' must be finite and not negative; no emission");
    }
};

}  // namespace

Material* newPhysicallyBasedMaterial(DeviceState& state) {
    return new PhysicallyBasedMaterial(state);
}

}  // namespace ripple::device
