// Light records: validation of the description's lights, emissive triangles turned into lights, the hdri
// sampling tables, and the power-proportional selection pdf and cdf stored in each record.
#include "core/scene/LightTable.h"

#include "core/scene/ShadingTables.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace ripple::core {

namespace {

constexpr float kPi = glm::pi<float>();

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Cosines of the spot profile's edges: none beyond openingAngle / 2, all within openingAngle / 2 - falloff.
glm::vec2 spotCosines(const Light& light) {
    const float outer = std::clamp(0.5f * light.openingAngle, 0.0f, kPi);
    const float inner = std::clamp(outer - std::max(light.falloffAngle, 0.0f), 0.0f, outer);
    return {std::cos(outer), std::cos(inner)};
}

// Word offset of the hdri tables: H floats of the row cdf, then W floats of each row's cdf; each row
// weighted by luminance times sin(theta) (the solid angle of its texels). Returns the mean luminance.
float appendEnvironmentTables(const Texture& texture, std::vector<uint32_t>& texels, uint32_t& offset) {
    const uint32_t w = texture.width, h = texture.height;
    std::vector<float> rows(h), cells(size_t(w) * h);
    double total = 0.0, luminanceSum = 0.0, solidAngleSum = 0.0;
    for (uint32_t y = 0; y < h; ++y) {
        const double sinTheta = std::sin(kPi * (y + 0.5) / h);
        double row = 0.0;
        for (uint32_t x = 0; x < w; ++x) {
            float rgba[4];
            std::memcpy(rgba, texture.texels.data() + 16 * (size_t(y) * w + x), sizeof(rgba));
            double l = std::isfinite(rgba[0] + rgba[1] + rgba[2]) ? std::max(0.0f, luminance({rgba[0], rgba[1], rgba[2]})) : 0.0;
            luminanceSum += l * sinTheta;
            row += l * sinTheta;
            cells[size_t(y) * w + x] = float(row);
        }
        solidAngleSum += sinTheta * w;
        for (uint32_t x = 0; x < w; ++x) cells[size_t(y) * w + x] = row > 0.0 ? float(cells[size_t(y) * w + x] / row) : float(x + 1) / w;
        cells[size_t(y) * w + w - 1] = 1.0f;
        total += row;
        rows[y] = float(total);
    }
    for (uint32_t y = 0; y < h; ++y) rows[y] = total > 0.0 ? float(rows[y] / total) : float(y + 1) / h;
    rows[h - 1] = 1.0f;
    offset = static_cast<uint32_t>(texels.size());
    for (float v : rows) texels.push_back(std::bit_cast<uint32_t>(v));
    for (float v : cells) texels.push_back(std::bit_cast<uint32_t>(v));
    return solidAngleSum > 0.0 ? float(luminanceSum / solidAngleSum) : 0.0f;
}

// False (with a message) when the light cannot be used.
bool convertLight(const Light& light, uint32_t index, const SceneDescription& description, ShadingTables& out,
                  gpu::LightRecord& r) {
    const std::string name = "light " + std::to_string(index);
    auto reject = [&](const std::string& why) {
        out.messages.push_back(name + ": " + why + "; skipped");
        ++out.lightsSkipped;
        return false;
    };
    if (!finite(light.color) || glm::any(glm::lessThan(light.color, glm::vec3(0.0f))) || !std::isfinite(light.intensity) ||
        light.intensity < 0.0f)
        return reject("color or intensity is negative, NaN or Inf");
    r = gpu::LightRecord{};
    r.emission = gpu::vec4(light.color * light.intensity, 0.0f);
    r.kind = static_cast<uint32_t>(light.kind);
    auto unitDirection = [&](const glm::vec3& v, glm::vec4& into) {
        const float length = finite(v) ? glm::length(v) : 0.0f;
        if (!(length > 0.0f && std::isfinite(length))) return false;
        into = gpu::vec4(v / length, 0.0f);
        return true;
    };
    switch (light.kind) {
    case Light::Kind::Directional:
        if (!unitDirection(light.direction, r.direction)) return reject("direction is zero, NaN or Inf");
        if (!(light.angularDiameter >= 0.0f && light.angularDiameter <= kPi))
            return reject("angularDiameter is outside [0, pi] or NaN");
        {
            // 1 - cos(d / 2) as 2 sin^2(d / 4): no cancellation for a sun's 0.0093 rad.
            const double s = std::sin(0.25 * double(light.angularDiameter));
            r.edge1.x = float(2.0 * s * s);
        }
        return true;
    case Light::Kind::Point:
        if (!finite(light.position)) return reject("position is NaN or Inf");
        r.position = gpu::vec4(light.position, 0.0f);
        return true;
    case Light::Kind::Spot:
    case Light::Kind::Ring: {
        if (!finite(light.position)) return reject("position is NaN or Inf");
        if (!unitDirection(light.direction, r.direction)) return reject("direction is zero, NaN or Inf");
        if (!std::isfinite(light.openingAngle) || !std::isfinite(light.falloffAngle)) return reject("openingAngle or falloffAngle is NaN or Inf");
        r.position = gpu::vec4(light.position, 0.0f);
        const glm::vec2 cosines = spotCosines(light);
        r.edge1 = gpu::vec4(cosines.x, cosines.y, 0.0f, 0.0f);
        if (light.kind == Light::Kind::Spot) return true;
        const float outer = light.radius, inner = std::max(light.innerRadius, 0.0f);
        if (!std::isfinite(outer) || !std::isfinite(inner)) return reject("radius or innerRadius is NaN or Inf");
        if (!(outer > inner)) {  // no area: a spot light at its centre, intensity taken as W/sr
            r.kind = gpu::LIGHT_SPOT;
            return true;
        }
        const float area = kPi * (outer * outer - inner * inner);
        r.edge1.z = outer;
        r.edge1.w = area;
        r.edge2 = gpu::vec4(0.0f, 0.0f, 0.0f, inner);
        return true;
    }
    case Light::Kind::Quad: {
        if (!finite(light.position) || !finite(light.edge1) || !finite(light.edge2))
            return reject("position or edges are NaN or Inf");
        const glm::vec3 n = glm::cross(light.edge1, light.edge2);
        const float area = glm::length(n);
        if (!(area > 0.0f && std::isfinite(area))) return reject("edges span no area");
        r.position = gpu::vec4(light.position, 0.0f);
        r.direction = gpu::vec4(n / area, 0.0f);
        r.edge1 = gpu::vec4(light.edge1, area);
        r.edge2 = gpu::vec4(light.edge2, 0.0f);
        r.twoSided = light.twoSided ? 1u : 0u;
        return true;
    }
    case Light::Kind::Hdri: {
        if (!unitDirection(light.direction, r.direction)) return reject("direction is zero, NaN or Inf");
        glm::vec3 up = light.up - glm::dot(light.up, glm::vec3(r.direction)) * glm::vec3(r.direction);
        if (!unitDirection(up, r.edge2)) return reject("up is zero, NaN, Inf or along direction");
        const bool usable = light.texture >= 0 && size_t(light.texture) < description.textures.size() &&
                            out.textures[light.texture].width > 0 &&
                            description.textures[light.texture].format == Texture::Format::Rgba32Float;
        if (!usable) return reject("needs a valid Rgba32Float texture");
        if (out.environmentLight >= 0) return reject("only one hdri light is used");
        r.texture = static_cast<uint32_t>(light.texture);
        return true;
    }
    }
    return reject("unknown kind " + std::to_string(static_cast<uint32_t>(light.kind)));
}

// One LIGHT_TRIANGLE per valid triangle of instances whose material is a light (MATERIAL_FLAG_LIGHT).
std::vector<gpu::LightRecord> triangleLights(const SceneDescription& description, const ShadingTables& out) {
    std::vector<gpu::LightRecord> lights;
    for (const InstanceDescription& inst : description.instances) {
        if (inst.geometry.kind != GeometryKind::Triangles || inst.geometry.index >= description.meshes.size()) continue;
        if (inst.materialIndex >= description.materials.size()) continue;
        const gpu::MaterialRecord& material = out.materials[inst.materialIndex];
        if ((material.flags & gpu::MATERIAL_FLAG_LIGHT) == 0 || !affineAndInvertible(inst.transform)) continue;
        const TriangleMesh& mesh = description.meshes[inst.geometry.index];
        const uint64_t count = mesh.indices.empty() ? mesh.positions.size() / 3 : mesh.indices.size();
        for (uint64_t t = 0; t < count; ++t) {
            const glm::uvec3 idx = mesh.indices.empty() ? glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2) : mesh.indices[t];
            if (idx.x >= mesh.positions.size() || idx.y >= mesh.positions.size() || idx.z >= mesh.positions.size()) continue;
            glm::vec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = glm::vec3(inst.transform * glm::vec4(mesh.positions[idx[k]], 1.0f));
            if (!finite(p[0]) || !finite(p[1]) || !finite(p[2])) continue;
            const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0], n = glm::cross(e1, e2);
            const float twiceArea = glm::length(n);
            if (!(twiceArea > 0.0f && std::isfinite(twiceArea))) continue;
            gpu::LightRecord r{};
            r.kind = gpu::LIGHT_TRIANGLE;
            r.emission = gpu::vec4(glm::vec3(material.emissiveIor), 0.0f);
            r.position = gpu::vec4(p[0], 0.0f);
            r.direction = gpu::vec4(n / twiceArea, 0.0f);
            r.edge1 = gpu::vec4(e1, 0.5f * twiceArea);
            r.edge2 = gpu::vec4(e2, 0.0f);
            r.twoSided = 1u;  // emissive surfaces emit from both sides
            lights.push_back(r);
        }
    }
    return lights;
}

bool tested(const gpu::LightRecord& r) {
    return r.kind == gpu::LIGHT_QUAD || r.kind == gpu::LIGHT_RING || r.kind == gpu::LIGHT_HDRI ||
           (r.kind == gpu::LIGHT_DIRECTIONAL && r.edge1.x > 0.0f);
}

}  // namespace

double lightSelectionPower(const gpu::LightRecord& light, float sceneRadius, float environmentLuminance) {
    const double l = luminance(glm::vec3(light.emission));
    const double disk = kPi * double(sceneRadius) * sceneRadius;
    switch (light.kind) {
    case gpu::LIGHT_DIRECTIONAL: return l * disk;
    case gpu::LIGHT_POINT: return l * 4.0f * kPi;
    case gpu::LIGHT_SPOT: return l * 2.0f * kPi * (1.0f - 0.5f * (light.edge1.x + light.edge1.y));
    case gpu::LIGHT_QUAD: return l * kPi * light.edge1.w * (light.twoSided ? 2.0f : 1.0f);
    case gpu::LIGHT_RING: return l * kPi * light.edge1.w;
    // What the triangle's pdf in lights.glsl (surfaceLightPdf) assumes: pi * area * luminance * 2 sides.
    case gpu::LIGHT_TRIANGLE: return l * kPi * light.edge1.w * 2.0f;
    case gpu::LIGHT_HDRI: return l * environmentLuminance * 4.0f * kPi * disk;
    }
    return 0.0f;
}

float ambientLightChance(const glm::vec3& ambient, float sceneRadius, float lightPowerTotal) {
    const double power = double(luminance(ambient)) * kPi * kPi * double(sceneRadius) * sceneRadius;
    if (!(power > 0.0) || !std::isfinite(power)) return 0.0f;
    // "No lights" as the kernels test it (sceneHasLights in lights.glsl): a total that is not above 0.
    if (!(lightPowerTotal > 0.0f)) return 1.0f;
    // Below 1 whenever there are lights, however faint, so that they keep a chance of being sampled.
    return std::min(float(power / (power + double(lightPowerTotal))), std::nextafter(1.0f, 0.0f));
}

void buildLightTable(const SceneDescription& description, float sceneRadius, ShadingTables& out) {
    std::vector<gpu::LightRecord> lights;
    float environmentLuminance = 0.0f;
    for (uint32_t i = 0; i < description.lights.size(); ++i) {
        gpu::LightRecord record;
        if (!convertLight(description.lights[i], i, description, out, record)) continue;
        if (record.kind == gpu::LIGHT_HDRI) {
            environmentLuminance = appendEnvironmentTables(description.textures[record.texture], out.texels, record.distribution);
            out.environmentLight = 0;  // set to its index below
        }
        lights.push_back(record);
    }
    std::vector<gpu::LightRecord> triangles = triangleLights(description, out);
    if (triangles.size() > kMaxTriangleLights) {
        out.messages.push_back(std::to_string(triangles.size()) + " emissive triangles are more than the " +
                               std::to_string(kMaxTriangleLights) + " that become lights; they emit, found by BSDF sampling only");
        for (gpu::MaterialRecord& m : out.materials) m.flags &= ~gpu::MATERIAL_FLAG_LIGHT;
        triangles.clear();
    }
    out.triangleLights = triangles.size();
    out.localTriangleLights = triangles;
    lights.insert(lights.end(), triangles.begin(), triangles.end());
    lights.insert(lights.end(), description.foreignTriangleLights.begin(), description.foreignTriangleLights.end());
    std::stable_partition(lights.begin(), lights.end(), tested);
    out.testedLightCount = static_cast<uint32_t>(std::count_if(lights.begin(), lights.end(), tested));

    double total = 0.0;
    std::vector<double> powers;
    for (const gpu::LightRecord& r : lights) {
        const double p = lightSelectionPower(r, sceneRadius, environmentLuminance);
        powers.push_back(std::isfinite(p) && p > 0.0 ? p : 0.0);
        total += powers.back();
    }
    double running = 0.0;
    for (size_t i = 0; i < lights.size(); ++i) {
        running += powers[i];
        lights[i].emission.w = total > 0.0 ? float(powers[i] / total) : 0.0f;
        lights[i].position.w = total > 0.0 ? float(running / total) : 0.0f;
        if (lights[i].kind == gpu::LIGHT_HDRI) out.environmentLight = static_cast<int32_t>(i);
    }
    if (!lights.empty() && total > 0.0) lights.back().position.w = 1.0f;
    out.lightPowerTotal = float(total);
    out.lights = std::move(lights);
}

}  // namespace ripple::core
