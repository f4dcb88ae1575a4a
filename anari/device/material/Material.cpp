// Parameter pulling shared by the material subtypes (see Material.h).
#include "anari/device/material/Material.h"

#include <algorithm>

#include "anari/device/object/ArrayChecks.h"

#include <cmath>
#include <string>

namespace ripple::device {

void Material::reset(core::Material::Kind kind, glm::vec3 baseColor) {
    forgetDependencies();
    material_ = core::Material{};
    material_.kind = kind;
    material_.baseColor = baseColor;
    samplers_.fill(nullptr);
    attributes_.fill(std::nullopt);
}

int32_t& textureIndexOf(core::Material& material, TextureSlot slot) {
    switch (slot) {
        case TextureSlot::Opacity: return material.opacityTexture;
        case TextureSlot::Metallic: return material.metallicTexture;
        case TextureSlot::Roughness: return material.roughnessTexture;
        case TextureSlot::Emissive: return material.emissiveTexture;
        case TextureSlot::Normal: return material.normalTexture;
        default: return material.baseColorTexture;
    }
}

bool Material::pullSampler(std::string_view name, TextureSlot slot) {
    auto* sampler = dynamic_cast<Sampler*>(getObject(name, ANARI_SAMPLER));
    if (!sampler) {
        reportWarning("parameter '" + std::string(name) + "' is not a sampler Ripple knows; ignored");
        return false;
    }
    useChild(sampler);
    samplers_[size_t(slot)] = sampler;
    return true;
}

bool Material::pullAttribute(std::string_view name, TextureSlot slot) {
    const std::string attribute = getString(name, "");
    const std::optional<core::Texture::Input> input = surfaceInputNamed(attribute);
    if (!input) {
        reportWarning("parameter '" + std::string(name) + "' names attribute '" + attribute +
                      "', which is not one of attribute0..3, color, primitiveId, worldPosition, worldNormal; ignored");
        return false;
    }
    attributes_[size_t(slot)] = input;
    return true;
}

void Material::pullBaseColor(std::string_view name) {
    std::string quotedName = "'";  // appended: GCC 12 -O3 warns falsely (-Wrestrict) on "'" + std::string
    quotedName.append(name).append("'");
    switch (parameterType(name)) {
        case ANARI_UNKNOWN: return;  // unset: the subtype's default
        case ANARI_FLOAT32_VEC3: material_.baseColor = get<glm::vec3>(name, material_.baseColor); break;
        case ANARI_FLOAT32_VEC4:
            material_.baseColor = glm::vec3(get<glm::vec4>(name, glm::vec4(material_.baseColor, 1)));
            break;
        case ANARI_SAMPLER:
            if (!pullSampler(name, TextureSlot::BaseColor)) return;
            // The texture multiplies baseColor, so a textured colour starts from white.
            material_.baseColor = glm::vec3(1.0f);
            break;
        case ANARI_STRING:
            if (getString(name, "") == "color") {
                material_.baseColorFromVertexColor = true;
            } else if (pullAttribute(name, TextureSlot::BaseColor)) {
                material_.baseColor = glm::vec3(1.0f);  // the attribute multiplies it, as a texture would
            }
            break;
        default:
            reportWarning("parameter " + quotedName + " has type " + ripple_anari::typeName(parameterType(name)) +
                          ", expected FLOAT32_VEC3, SAMPLER or STRING; using the default colour");
            (void)findParameter(name);
    }
    if (reject(nonFiniteProblem(name, material_.baseColor))) material_.baseColor = glm::vec3(0.0f);
}

float Material::pullFactor(std::string_view name, float fallback, TextureSlot slot) {
    if (parameterType(name) == ANARI_SAMPLER) return pullSampler(name, slot) ? 1.0f : fallback;
    if (parameterType(name) == ANARI_STRING) return pullAttribute(name, slot) ? 1.0f : fallback;
    return pullValue(name, fallback);
}

float Material::pullValue(std::string_view name, float fallback) {
    const ANARIDataType type = parameterType(name);
    if (type == ANARI_SAMPLER || type == ANARI_STRING) {
        (void)findParameter(name);
        reportWarning("parameter '" + std::string(name) + "' as a " + ripple_anari::typeName(type) +
                      " is not supported yet; using " + std::to_string(fallback));
        return fallback;
    }
    const float value = get<float>(name, fallback);
    return reject(nonFiniteProblem(name, value)) ? fallback : value;
}

void Material::pullAlphaMode() {
    const std::string mode = getString("alphaMode", "opaque");
    material_.alphaCutoff = std::clamp(get<float>("alphaCutoff", 0.5f), 0.0f, 1.0f);
    if (mode == "opaque") material_.alphaMode = core::Material::AlphaMode::Opaque;
    else if (mode == "blend") material_.alphaMode = core::Material::AlphaMode::Blend;
    else if (mode == "mask") material_.alphaMode = core::Material::AlphaMode::Mask;
    else {
        reportWarning("alphaMode '" + mode + "' is not one of opaque, blend, mask; 'opaque' used");
        material_.alphaMode = core::Material::AlphaMode::Opaque;
    }
}

}  // namespace ripple::device
