// ANARI material: matte and physicallyBased become a core::Material. A colour may be a value, a sampler
// or the name of a surface attribute ("color", "attribute0".."attribute3", ...); opacity, metallic,
// roughness and emissive may come from samplers and attributes too, normal from a sampler.
#pragma once

#include <array>

#include "anari/device/sampler/Sampler.h"
#include "anari/device/scene/SceneObject.h"
#include "core/scene/SceneDescription.h"

namespace ripple::device {

// The material parameters a sampler can drive; each names one texture index of core::Material.
enum class TextureSlot : size_t { BaseColor, Opacity, Metallic, Roughness, Emissive, Normal, Count };
inline constexpr size_t kTextureSlotCount = size_t(TextureSlot::Count);

// The texture index of `material` that `slot` fills.
int32_t& textureIndexOf(core::Material& material, TextureSlot slot);

class Material : public SceneObject {
public:
    Material(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_MATERIAL, std::move(subtype)) {}

    // The committed material. Its texture indices stay kNoTexture: they only exist in a scene
    // description, so SceneSync fills them in from sampler().
    const core::Material& material() const { return material_; }
    // The sampler driving `slot`, or nullptr.
    Sampler* sampler(TextureSlot slot) const { return samplers_[size_t(slot)]; }
    // The surface attribute driving `slot` (a parameter given as an attribute name), if any. SceneSync
    // makes it a transform texture of that input, which multiplies the factor as a sampler would.
    std::optional<core::Texture::Input> attribute(TextureSlot slot) const { return attributes_[size_t(slot)]; }

protected:
    // For commit(): starts over from the subtype's defaults.
    void reset(core::Material::Kind kind, glm::vec3 baseColor);
    // The base colour from `name`: FLOAT32_VEC3 or VEC4 (alpha ignored), a sampler, or the string "color".
    void pullBaseColor(std::string_view name);
    // A factor that ANARI allows to be a value, a sampler or an attribute. A sampler or an attribute drives
    // `slot` (its first component multiplies the factor, which becomes 1).
    float pullFactor(std::string_view name, float fallback, TextureSlot slot);
    // A factor only a value may give (no core texture for it): samplers and attributes are reported.
    float pullValue(std::string_view name, float fallback);
    // A sampler parameter for `slot`; false (reported) when `name` is set but is not a usable sampler.
    bool pullSampler(std::string_view name, TextureSlot slot);
    // A STRING parameter naming the surface attribute that drives `slot`; false (reported) for an unknown name.
    bool pullAttribute(std::string_view name, TextureSlot slot);
    // alphaMode (opaque, blend, mask) and alphaCutoff.
    void pullAlphaMode();

    core::Material material_;

private:
    std::array<Sampler*, kTextureSlotCount> samplers_{};  // kept alive by useChild()
    std::array<std::optional<core::Texture::Input>, kTextureSlotCount> attributes_{};
};

Material* newMatteMaterial(DeviceState& state);
Material* newPhysicallyBasedMaterial(DeviceState& state);

}  // namespace ripple::device
