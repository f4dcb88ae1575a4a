// Renderer parameters: "background" (KHR_RENDERER_BACKGROUND_COLOR), "ambientColor" and
// "ambientRadiance" (KHR_RENDERER_AMBIENT_LIGHT), "pixelSamples", "maxPathLength", "maxRadiance", "seed" and
// "volumeAnisotropy"; "eyeLight" also reads "eyeLightBlendRatio", and its ambient light is the light at the
// eye (radiance 1 unless set).
#include "anari/device/renderer/Renderer.h"

#include "anari/device/scene/ArrayConversion.h"

#include <cmath>
#include <string>

namespace ripple::device {

void Renderer::commit() {
    settings_ = core::RenderSettings{};
    const bool eyeLight = subtype() == "eyeLight";
    if (eyeLight) {
        settings_.shading = core::RenderSettings::Shading::EyeLight;
        settings_.ambientRadiance = 1.0f;
        settings_.eyeLightBlendRatio = get<float>("eyeLightBlendRatio", settings_.eyeLightBlendRatio);
        if (!(settings_.eyeLightBlendRatio >= 0.0f && settings_.eyeLightBlendRatio <= 1.0f)) {
            reportWarning("parameter 'eyeLightBlendRatio' must be within [0, 1]; using 0.5");
            settings_.eyeLightBlendRatio = 0.5f;
        }
    }
    settings_.background = get<glm::vec4>("background", settings_.background);
    if (!allFinite(settings_.background)) {
        reportWarning("parameter 'background' is not finite; using opaque black");
        settings_.background = glm::vec4(0, 0, 0, 1);
    }
    settings_.ambientColor = get<glm::vec3>("ambientColor", settings_.ambientColor);
    settings_.ambientRadiance = get<float>("ambientRadiance", settings_.ambientRadiance);
    ambientGiven_ = has("ambientRadiance");
    if (!allFinite(settings_.ambientColor) || !std::isfinite(settings_.ambientRadiance) ||
        settings_.ambientRadiance < 0.0f || glm::any(glm::lessThan(settings_.ambientColor, glm::vec3(0.0f)))) {
        reportWarning(
            "parameters 'ambientColor' and 'ambientRadiance' must be finite and not negative; no ambient light");
        settings_.ambientColor = glm::vec3(1.0f);
        settings_.ambientRadiance = 0.0f;
    }
    // Bounds keep one renderFrame call and one path of a bounded length (lavapipe runs everything on the CPU).
    settings_.pixelSamples = pullCount("pixelSamples", settings_.pixelSamples, 1024);
    settings_.maxPathLength = pullCount("maxPathLength", settings_.maxPathLength, 64);
    // A clamp on single contributions (biased, less noise); 0, the default, turns it off.
    settings_.maxRadiance = get<float>("maxRadiance", 0.0f);
    if (!std::isfinite(settings_.maxRadiance) || settings_.maxRadiance < 0.0f) {
        reportWarning("parameter 'maxRadiance' must be finite and not negative; no clamp");
        settings_.maxRadiance = 0.0f;
    }
    // Scattering in volumes: the Henyey-Greenstein mean cosine g (0, the default, is isotropic).
    settings_.phaseAnisotropy = get<float>("volumeAnisotropy", 0.0f);
    if (!std::isfinite(settings_.phaseAnisotropy) || std::abs(settings_.phaseAnisotropy) >= 1.0f) {
        reportWarning("parameter 'volumeAnisotropy' must be finite and within (-1, 1); using 0 (isotropic)");
        settings_.phaseAnisotropy = 0.0f;
    }
    // Two images with different seeds share no random numbers: a reference rendered with one judges an image
    // rendered with another without sharing its samples. INT32 (bit pattern kept) or UINT32.
    if (parameterType("seed") == ANARI_INT32)
        settings_.seed = uint32_t(get<int32_t>("seed", 0));
    else
        settings_.seed = get<uint32_t>("seed", 0u);
}

uint32_t Renderer::pullCount(std::string_view name, uint32_t fallback, uint32_t most) {
    int64_t value = fallback;
    if (parameterType(name) == ANARI_INT32)
        value = get<int32_t>(name, int32_t(fallback));
    else if (has(name))
        value = get<uint32_t>(name, fallback);
    if (value < 1 || value > int64_t(most)) {
        reportWarning("parameter '" + std::string(name) + "' must be between 1 and " + std::to_string(most) +
                      "; using " + std::to_string(fallback));
        return fallback;
    }
    return uint32_t(value);
}

}  // namespace ripple::device
