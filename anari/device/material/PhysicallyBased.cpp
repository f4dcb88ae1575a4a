// Material subtype "physicallyBased" (KHR_MATERIAL_PHYSICALLY_BASED): the glTF metallic-roughness model.
// baseColor, opacity (alphaMode, alphaCutoff), metallic, roughness, emissive, normal, ior, specular,
// transmission, clearcoat and clearcoatRoughness are used (baseColor, opacity, metallic, roughness,
// emissive and normal also from samplers, all but normal also from surface attributes); sheen, iridescence, thickness and attenuation are not yet,
// and are reported as unused parameters when set.
#include "anari/device/material/Material.h"
#include "anari/device/object/ArrayChecks.h"

#include <algorithm>

namespace ripple::device {
namespace {

class PhysicallyBasedMaterial final : public Material {
public:
    explicit PhysicallyBasedMaterial(DeviceState& state) : Material(state, "physicallyBased") {}

    void commit() override {
        reset(core::Material::Kind::PhysicallyBased, glm::vec3(1.0f));
        pullBaseColor("baseColor");
        material_.opacity = std::clamp(pullFactor("opacity", 1.0f, TextureSlot::Opacity), 0.0f, 1.0f);
        material_.metallic = std::clamp(pullFactor("metallic", 1.0f, TextureSlot::Metallic), 0.0f, 1.0f);
        material_.roughness = std::clamp(pullFactor("roughness", 1.0f, TextureSlot::Roughness), 0.0f, 1.0f);
        material_.ior = std::max(pullValue("ior", 1.5f), 1.0f);
        // Ripple follows glTF's KHR_materials_specular, where 1 keeps the ior's reflectance (ANARI's table
        // lists 0, which would remove dielectric reflection from every default material).
        material_.specular = std::clamp(pullValue("specular", 1.0f), 0.0f, 1.0f);
        material_.transmission = std::clamp(pullValue("transmission", 0.0f), 0.0f, 1.0f);
        material_.clearcoat = std::clamp(pullValue("clearcoat", 0.0f), 0.0f, 1.0f);
        material_.clearcoatRoughness = std::clamp(pullValue("clearcoatRoughness", 0.0f), 0.0f, 1.0f);
        pullEmissive();
        if (parameterType("normal") == ANARI_SAMPLER) pullSampler("normal", TextureSlot::Normal);
        else if (has("normal")) reportWarning("parameter 'normal' must be a sampler (a tangent-space normal map); ignored");
        pullAlphaMode();
    }

private:
    void pullEmissive() {
        const ANARIDataType type = parameterType("emissive");
        if (type == ANARI_UNKNOWN) return;
        // A sampler's rgb is the emitted radiance (the surface then is not sampled as a light).
        if (type == ANARI_SAMPLER || type == ANARI_STRING) {
            const bool driven = type == ANARI_SAMPLER ? pullSampler("emissive", TextureSlot::Emissive)
                                                      : pullAttribute("emissive", TextureSlot::Emissive);
            if (driven) material_.emissive = glm::vec3(1.0f);
            return;
        }
        if (type != ANARI_FLOAT32_VEC3) {
            (void)findParameter("emissive");
            reportWarning("parameter 'emissive' as " + std::string(ripple_anari::typeName(type)) +
                          " is not supported yet (FLOAT32_VEC3 only); no emission");
            return;
        }
        const glm::vec3 emissive = get<glm::vec3>("emissive", glm::vec3(0.0f));
        if (reject(nonFiniteProblem("emissive", emissive))) return;
        if (glm::all(glm::greaterThanEqual(emissive, glm::vec3(0.0f))))
            material_.emissive = emissive;
        else
            reportWarning("parameter 'emissive' is negative; no emission");
    }
};

}  // namespace

Material* newPhysicallyBasedMaterial(DeviceState& state) {
    return new PhysicallyBasedMaterial(state);
}

}  // namespace ripple::device
