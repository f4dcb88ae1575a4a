// What every sampler subtype shares: the ANARI names of the surface attributes a sampler can read.
#include "anari/device/sampler/Sampler.h"

#include <array>
#include <string>
#include <utility>

namespace ripple::device {

std::optional<core::Texture::Input> surfaceInputNamed(std::string_view name) {
    using Input = core::Texture::Input;
    static constexpr std::array<std::pair<std::string_view, Input>, 8> kNames{{
        {"attribute0", Input::Attribute0}, {"attribute1", Input::Attribute1}, {"attribute2", Input::Attribute2},
        {"attribute3", Input::Attribute3}, {"color", Input::Color}, {"primitiveId", Input::PrimitiveId},
        {"worldPosition", Input::WorldPosition}, {"worldNormal", Input::WorldNormal},
    }};
    for (const auto& [known, input] : kNames)
        if (name == known) return input;
    return std::nullopt;
}

core::Texture::Input Sampler::pullInAttribute() {
    const std::string name = getString("inAttribute", "attribute0");
    if (const std::optional<core::Texture::Input> input = surfaceInputNamed(name)) return *input;
    reportWarning("parameter 'inAttribute' has unknown value '" + name +
                  "' (expected attribute0..3, color, primitiveId, worldPosition or worldNormal); using 'attribute0'");
    return core::Texture::Input::Attribute0;
}

}  // namespace ripple::device
