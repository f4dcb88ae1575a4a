// Light subtype "hdri" (KHR_LIGHT_HDRI): an equirectangular environment of "radiance" (ARRAY2D of
// FLOAT32_VEC3 or VEC4, W/sr/m^2) times "scale" and "color"; the image centre is seen along "direction",
// its top row towards "up". Core importance-samples it by the image's luminance.
#include "anari/device/light/Light.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <cstring>
#include <string>

namespace ripple::device {
namespace {

class HdriLight final : public Light {
public:
    explicit HdriLight(DeviceState& state) : Light(state, "hdri") {}

    const core::Texture* image() const override { return image_.width > 0 ? &image_ : nullptr; }

    void commit() override {
        forgetDependencies();
        light_ = core::Light{};
        image_ = core::Texture{};
        light_.kind = core::Light::Kind::Hdri;
        light_.color = pullColor();
        light_.direction = get<glm::vec3>("direction", glm::vec3(1.0f, 0.0f, 0.0f));
        light_.up = get<glm::vec3>("up", glm::vec3(0.0f, 0.0f, 1.0f));
        light_.intensity = pullAmount("scale").value_or(1.0f);
        const std::string layout = getString("layout", "equirectangular");
        if (layout != "equirectangular") {
            invalidate("layout '" + layout + "' is not supported (only 'equirectangular')");
            return;
        }
        if (reject(nonFiniteProblem("direction", light_.direction)) || reject(nonFiniteProblem("up", light_.up)))
            return;
        Array* radiance = getArray("radiance", ANARI_ARRAY2D);
        if (!radiance) {
            invalidate(has("radiance") ? "parameter 'radiance' must be an ARRAY2D" : "missing required parameter 'radiance'");
            return;
        }
        useArray(radiance);
        const ANARIDataType type = radiance->elementType();
        if (type != ANARI_FLOAT32_VEC3 && type != ANARI_FLOAT32_VEC4) {
            invalidate(elementTypeProblem("radiance", type, "FLOAT32_VEC3 or FLOAT32_VEC4"));
            return;
        }
        if (radiance->dim(0) == 0 || radiance->dim(1) == 0) {
            invalidate("parameter 'radiance' is empty");
            return;
        }
        const std::vector<glm::vec4> texels = *readFloatVectors(*radiance, glm::vec4(0, 0, 0, 1));
        if (std::optional<std::string> problem = nonFiniteProblem("radiance", texels, "texel")) {
            invalidate(*problem);
            return;
        }
        for (size_t i = 0; i < texels.size(); ++i)
            if (glm::any(glm::lessThan(glm::vec3(texels[i]), glm::vec3(0.0f)))) {
                invalidate("parameter 'radiance' texel " + std::to_string(i) + " is negative");
                return;
            }
        image_.width = uint32_t(radiance->dim(0));
        image_.height = uint32_t(radiance->dim(1));
        image_.format = core::Texture::Format::Rgba32Float;
        image_.wrapS = core::Texture::Wrap::Repeat;  // longitude wraps around, latitude ends at the poles
        image_.wrapT = core::Texture::Wrap::ClampToEdge;
        image_.texels.resize(texels.size() * sizeof(glm::vec4));
        std::memcpy(image_.texels.data(), texels.data(), image_.texels.size());
    }

private:
    core::Texture image_;
};

}  // namespace

Light* newHdriLight(DeviceState& state) { return new HdriLight(state); }

}  // namespace ripple::device
