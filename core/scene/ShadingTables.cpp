// Validation and conversion of materials and textures into the GPU records the shading kernels read; the
// BSDF energy tables and the lights (core/scene/LightTable.cpp) are appended.
#include "core/scene/ShadingTables.h"

#include "core/scene/BsdfTables.h"
#include "core/scene/LightTable.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace ripple::core {

namespace {

bool finite(float x) { return std::isfinite(x); }
bool finite(const glm::vec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && finite(v.w); }
bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!finite(m[c][r])) return false;
    return true;
}
bool nonNegative(const glm::vec3& v) { return finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }

std::string join(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
    return out;
}

uint32_t bytesPerTexel(Texture::Format format) { return format == Texture::Format::Rgba32Float ? 16u : 4u; }

// Appends a texture's words to `texels` and fills its record; false (with a message) when it is unusable.
bool convertTexture(const Texture& texture, uint32_t index, ShadingTables& out, gpu::TextureRecord& record) {
    const std::string name = "texture " + std::to_string(index);
    if (texture.format != Texture::Format::Rgba8Unorm && texture.format != Texture::Format::Rgba8Srgb &&
        texture.format != Texture::Format::Rgba32Float) {
        out.messages.push_back(name + ": unknown format " + std::to_string(static_cast<uint32_t>(texture.format)) +
                               "; materials sample it as absent");
        return false;
    }
    if (static_cast<uint32_t>(texture.kind) > gpu::TEXTURE_KIND_PRIMITIVE ||
        static_cast<uint32_t>(texture.input) > gpu::TEXTURE_INPUT_WORLD_NORMAL) {
        out.messages.push_back(name + ": unknown kind " + std::to_string(static_cast<uint32_t>(texture.kind)) +
                               " or input " + std::to_string(static_cast<uint32_t>(texture.input)) +
                               "; materials sample it as absent");
        return false;
    }
    // A transform sampler has no image; a primitive sampler's image is one row.
    const bool imageless = texture.kind == Texture::Kind::Transform;
    const uint64_t expected = uint64_t(texture.width) * texture.height * texture.depth * bytesPerTexel(texture.format);
    const bool sized = imageless ? texture.texels.empty()
                                 : texture.width > 0 && texture.height > 0 && texture.depth > 0 &&
                                       (texture.kind == Texture::Kind::Image || (texture.height == 1 && texture.depth == 1));
    if (!sized || texture.texels.size() != expected) {
        std::string size = std::to_string(texture.width) + "x" + std::to_string(texture.height);
        if (texture.depth != 1) size.append("x").append(std::to_string(texture.depth));
        out.messages.push_back(name + ": " + std::to_string(texture.texels.size()) + " bytes of texels for " +
                               size + " (need " + std::to_string(expected) +
                               (imageless ? ", and none for a transform" : ", and a nonzero size") +
                               "); materials sample it as absent");
        return false;
    }
    record.kind = static_cast<uint32_t>(texture.kind);
    record.inputAttribute = static_cast<uint32_t>(texture.input);
    record.width = texture.width;
    record.height = texture.height;
    record.depth = texture.depth;
    record.format = static_cast<uint32_t>(texture.format);
    record.texelOffset = static_cast<uint32_t>(out.texels.size());
    record.primitiveOffset = texture.primitiveOffset;
    auto wrap = [&](Texture::Wrap w, const char* axis) {
        if (w == Texture::Wrap::Repeat || w == Texture::Wrap::ClampToEdge || w == Texture::Wrap::MirrorRepeat)
            return static_cast<uint32_t>(w);
        out.messages.push_back(name + ": unknown wrap mode " + std::to_string(static_cast<uint32_t>(w)) + " for " +
                               axis + "; repeat used");
        return gpu::WRAP_REPEAT;
    };
    record.wrapS = wrap(texture.wrapS, "s");
    record.wrapT = wrap(texture.wrapT, "t");
    record.wrapR = wrap(texture.wrapR, "r");
    record.linearFilter = texture.linearFilter ? 1u : 0u;
    const bool transformsFinite = finite(texture.inTransform) && finite(texture.outTransform) &&
                                  finite(texture.inOffset) && finite(texture.outOffset);
    if (!transformsFinite) out.messages.push_back(name + ": non-finite in/out transform or offset; identity used");
    for (int c = 0; c < 4; ++c) {
        record.inTransform[c] = transformsFinite ? texture.inTransform[c] : glm::mat4(1.0f)[c];
        record.outTransform[c] = transformsFinite ? texture.outTransform[c] : glm::mat4(1.0f)[c];
    }
    record.inOffset = transformsFinite ? texture.inOffset : glm::vec4(0.0f);
    record.outOffset = transformsFinite ? texture.outOffset : glm::vec4(0.0f);

    const size_t first = out.texels.size();
    out.texels.resize(first + texture.texels.size() / 4);
    // memcpy with a null pointer is undefined even for 0 bytes, and an empty vector's data() may be null.
    if (!texture.texels.empty()) std::memcpy(out.texels.data() + first, texture.texels.data(), texture.texels.size());
    if (texture.format == Texture::Format::Rgba32Float) {
        uint64_t repaired = 0;
        for (size_t i = first; i < out.texels.size(); ++i) {
            float value;
            std::memcpy(&value, &out.texels[i], sizeof(value));
            if (!finite(value)) { out.texels[i] = 0u; ++repaired; }
        }
        if (repaired) out.messages.push_back(name + ": " + std::to_string(repaired) + " NaN or Inf texel value(s) replaced by 0");
        out.texelsRepaired += repaired;
    }
    return true;
}

gpu::MaterialRecord convertMaterial(const Material& m, uint32_t index, const std::vector<bool>& textureUsable,
                                    ShadingTables& out) {
    const Material defaults;
    std::vector<std::string> repaired;
    auto scalar = [&](float value, float fallback, float lo, float hi, const char* field) {
        if (!finite(value)) { repaired.push_back(field); return fallback; }
        if (value < lo || value > hi) { repaired.push_back(field); return std::fmin(std::fmax(value, lo), hi); }
        return value;
    };
    gpu::MaterialRecord r{};
    r.kind = static_cast<uint32_t>(m.kind);
    if (m.kind != Material::Kind::Matte && m.kind != Material::Kind::PhysicallyBased) {
        repaired.push_back("kind (matte used)");
        r.kind = gpu::MATERIAL_MATTE;
    }
    glm::vec3 base = m.baseColor;
    if (!nonNegative(base)) { repaired.push_back("baseColor"); base = defaults.baseColor; }
    glm::vec3 emissive = m.emissive;
    if (!nonNegative(emissive)) { repaired.push_back("emissive"); emissive = glm::vec3(0.0f); }
    const float opacity = scalar(m.opacity, 1.0f, 0.0f, 1.0f, "opacity");
    r.metallic = scalar(m.metallic, defaults.metallic, 0.0f, 1.0f, "metallic");
    r.roughness = scalar(m.roughness, defaults.roughness, 0.0f, 1.0f, "roughness");
    const float ior = scalar(m.ior, defaults.ior, 1e-3f, 1e3f, "ior");
    r.baseColorOpacity = gpu::vec4(base, opacity);
    r.emissiveIor = gpu::vec4(emissive, ior);
    r.flags = m.baseColorFromVertexColor ? gpu::MATERIAL_FLAG_VERTEX_COLOR : 0u;
    r.alphaMode = static_cast<uint32_t>(m.alphaMode);
    if (r.alphaMode > gpu::ALPHA_MASK) { repaired.push_back("alphaMode"); r.alphaMode = gpu::ALPHA_BLEND; }
    r.alphaCutoff = scalar(m.alphaCutoff, defaults.alphaCutoff, 0.0f, 1.0f, "alphaCutoff");
    r.specular = scalar(m.specular, defaults.specular, 0.0f, 1.0f, "specular");
    r.transmission = scalar(m.transmission, 0.0f, 0.0f, 1.0f, "transmission");
    r.clearcoat = scalar(m.clearcoat, 0.0f, 0.0f, 1.0f, "clearcoat");
    r.clearcoatRoughness = scalar(m.clearcoatRoughness, 0.0f, 0.0f, 1.0f, "clearcoatRoughness");
    auto texture = [&](int32_t textureIndex, const char* field) {
        if (textureIndex == kNoTexture) return gpu::NO_TEXTURE;
        const bool inRange = textureIndex >= 0 && size_t(textureIndex) < textureUsable.size();
        if (inRange && textureUsable[textureIndex]) return textureIndex;
        if (!inRange) repaired.push_back(std::string(field) + " " + std::to_string(textureIndex) + " (no such texture)");
        return gpu::NO_TEXTURE;
    };
    r.baseColorTexture = texture(m.baseColorTexture, "baseColorTexture");
    r.normalTexture = texture(m.normalTexture, "normalTexture");
    r.metallicTexture = texture(m.metallicTexture, "metallicTexture");
    r.roughnessTexture = texture(m.roughnessTexture, "roughnessTexture");
    r.emissiveTexture = texture(m.emissiveTexture, "emissiveTexture");
    r.opacityTexture = texture(m.opacityTexture, "opacityTexture");
    // Its triangles become lights (LightTable) when the emission is the same everywhere on it.
    if (glm::any(glm::greaterThan(emissive, glm::vec3(0.0f))) && r.emissiveTexture == gpu::NO_TEXTURE)
        r.flags |= gpu::MATERIAL_FLAG_LIGHT;
    if (!repaired.empty()) {
        out.messages.push_back("material " + std::to_string(index) + ": invalid " + join(repaired) + "; replaced by the default or clamped");
        ++out.materialsRepaired;
    }
    return r;
}

}  // namespace

ShadingTables buildShadingTables(const SceneDescription& description, float sceneRadius) {
    ShadingTables out;
    std::vector<bool> textureUsable(description.textures.size(), false);
    out.textures.resize(description.textures.size());
    for (uint32_t i = 0; i < description.textures.size(); ++i) {
        gpu::TextureRecord& record = out.textures[i];
        record = gpu::TextureRecord{};
        textureUsable[i] = convertTexture(description.textures[i], i, out, record);
        if (!textureUsable[i]) ++out.texturesSkipped;
    }
    for (uint32_t i = 0; i < description.materials.size(); ++i)
        out.materials.push_back(convertMaterial(description.materials[i], i, textureUsable, out));
    out.materials.push_back(convertMaterial(Material{}, defaultMaterialIndex(description), textureUsable, out));
    out.bsdfTableOffset = static_cast<uint32_t>(out.texels.size());
    for (float v : bsdfEnergyTables()) out.texels.push_back(std::bit_cast<uint32_t>(v));
    buildLightTable(description, sceneRadius, out);
    return out;
}

}  // namespace ripple::core
