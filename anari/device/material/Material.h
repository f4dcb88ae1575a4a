// ANARI material: matte and physicallyBased become a core::Material. A colour may be a value, a sampler
// (an image texture) or the string "color" (the geometry's colour attribute).
#pragma once

#include "anari/device/sampler/Sampler.h"
#include "anari/device/scene/SceneObject.h"
#include "core/scene/SceneDescription.h"

namespace ripple::device {

class Material : public SceneObject {
public:
    Material(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_MATERIAL, std::move(subtype)) {}

    // The committed material. Its baseColorTexture stays kNoTexture: the texture index only exists in a
    // scene description, so SceneSync fills it in from baseColorSampler().
    const core::Material& material() const { return material_; }
    Sampler* baseColorSampler() const { return baseColorSampler_; }

protected:
    // For commit(): starts over from the subtype's defaults.
    void reset(core::Material::Kind kind, glm::vec3 baseColor);
    // The base colour from `name`: FLOAT32_VEC3 or VEC4 (alpha ignored), a sampler, or the string "color".
    void pullBaseColor(std::string_view name);
    // A factor that ANARI allows to be a value, a sampler or an attribute; only values are supported
    // (the others are reported and the fallback used).
    float pullFactor(std::string_view name, float fallback);
    // alphaMode (opaque, blend, mask) and alphaCutoff.
    void pullAlphaMode();

    core::Material material_;

private:
    Sampler* baseColorSampler_ = nullptr;  // kept alive by useChild()
};

Material* newMatteMaterial(DeviceState& state);
Material* newPhysicallyBasedMaterial(DeviceState& state);

}  // namespace ripple::device
