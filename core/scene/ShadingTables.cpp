// Validation and conversion of materials, textures and lights into the GPU records the shading kernels read.
#include "core/scene/ShadingTables.h"

#include <cmath>
#include <cstring>

namespace ripple::core {

namespace {

bool finite(float x) { return std::isfinite(x); }
bool finite(const glm::vec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
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
    const uint64_t expected = uint64_t(texture.width) * texture.height * bytesPerTexel(texture.format);
    if (texture.width == 0 || texture.height == 0 || texture.texels.size() != expected) {
        out.messages.push_back(name + ": " + std::to_string(texture.texels.size()) + " bytes of texels for " +
                               std::to_string(texture.width) + "x" + std::to_string(texture.height) + " (need " +
                               std::to_string(expected) + ", and a nonzero size); materials sample it as absent");
        return false;
    }
    record.width = texture.width;
    record.height = texture.height;
    record.format = static_cast<uint32_t>(texture.format);
    record.texelOffset = static_cast<uint32_t>(out.texels.size());
    auto wrap = [&](Texture::Wrap w, const char* axis) {
        if (w == Texture::Wrap::Repeat || w == Texture::Wrap::ClampToEdge || w == Texture::Wrap::MirrorRepeat)
            return static_cast<uint32_t>(w);
        out.messages.push_back(name + ": unknown wrap mode " + std::to_string(static_cast<uint32_t>(w)) + " for " +
                               axis + "; repeat used");
        return gpu::WRAP_REPEAT;
    };
    record.wrapS = wrap(texture.wrapS, "s");
    record.wrapT = wrap(texture.wrapT, "t");
    record.linearFilter = texture.linearFilter ? 1u : 0u;
    const bool transformsFinite = finite(texture.inTransform) && finite(texture.outTransform);
    if (!transformsFinite) out.messages.push_back(name + ": non-finite in/out transform; identity used");
    for (int c = 0; c < 4; ++c) {
        record.inTransform[c] = transformsFinite ? texture.inTransform[c] : glm::mat4(1.0f)[c];
        record.outTransform[c] = transformsFinite ? texture.outTransform[c] : glm::mat4(1.0f)[c];
    }

    const size_t first = out.texels.size();
    out.texels.resize(first + texture.texels.size() / 4);
    std::memcpy(out.texels.data() + first, texture.texels.data(), texture.texels.size());
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
    r.baseColorTexture = gpu::NO_TEXTURE;
    if (m.baseColorTexture != kNoTexture) {
        const bool inRange = m.baseColorTexture >= 0 && size_t(m.baseColorTexture) < textureUsable.size();
        if (inRange && textureUsable[m.baseColorTexture]) r.baseColorTexture = m.baseColorTexture;
        else if (!inRange) repaired.push_back("baseColorTexture " + std::to_string(m.baseColorTexture) + " (no such texture)");
    }
    if (!repaired.empty()) {
        out.messages.push_back("material " + std::to_string(index) + ": invalid " + join(repaired) + "; replaced by the default or clamped");
        ++out.materialsRepaired;
    }
    return r;
}

// False (with a message) when the light cannot be used.
bool convertLight(const Light& light, uint32_t index, ShadingTables& out, gpu::LightRecord& r) {
    const std::string name = "light " + std::to_string(index);
    auto reject = [&](const std::string& why) {
        out.messages.push_back(name + ": " + why + "; skipped");
        ++out.lightsSkipped;
        return false;
    };
    if (!nonNegative(light.color) || !finite(light.intensity) || light.intensity < 0.0f)
        return reject("color or intensity is negative, NaN or Inf");
    r = gpu::LightRecord{};
    r.emission = gpu::vec4(light.color * light.intensity, 0.0f);
    r.kind = static_cast<uint32_t>(light.kind);
    switch (light.kind) {
    case Light::Kind::Directional: {
        const float length = finite(light.direction) ? glm::length(light.direction) : 0.0f;
        if (!(length > 0.0f && finite(length))) return reject("direction is zero, NaN or Inf");
        r.direction = gpu::vec4(light.direction / length, 0.0f);
        return true;
    }
    case Light::Kind::Point:
        if (!finite(light.position)) return reject("position is NaN or Inf");
        r.position = gpu::vec4(light.position, 1.0f);
        return true;
    case Light::Kind::Quad: {
        if (!finite(light.position) || !finite(light.edge1) || !finite(light.edge2))
            return reject("position or edges are NaN or Inf");
        const glm::vec3 n = glm::cross(light.edge1, light.edge2);
        const float area = glm::length(n);
        if (!(area > 0.0f && finite(area))) return reject("edges span no area");
        r.position = gpu::vec4(light.position, 1.0f);
        r.direction = gpu::vec4(n / area, 0.0f);
        r.edge1 = gpu::vec4(light.edge1, area);
        r.edge2 = gpu::vec4(light.edge2, 0.0f);
        r.twoSided = light.twoSided ? 1u : 0u;
        return true;
    }
    }
    return reject("unknown kind " + std::to_string(static_cast<uint32_t>(light.kind)));
}

}  // namespace

ShadingTables buildShadingTables(const SceneDescription& description) {
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
    for (uint32_t i = 0; i < description.lights.size(); ++i) {
        gpu::LightRecord record;
        if (convertLight(description.lights[i], i, out, record)) out.lights.push_back(record);
    }
    return out;
}

}  // namespace ripple::core
