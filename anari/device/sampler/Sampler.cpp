// What every sampler subtype shares: the ANARI names of the surface attributes a sampler can read.
#include "anari/device/sampler/Sampler.h"

#include <array>
#include <string>
#include <utility>

namespace ripple::device {

core::Texture::Input Sampler::pullInAttribute() {
    using Input = core::Texture::Input;
    static constexpr std::array<std::pair<std::string_view, Input>, 8> kNames{{
        {"attribute0", Input::Attribute0}, {"attribute1", Input::Attribute1}, {"attribute2", Input::Attribute2},
        {"attribute3", Input::Attribute3}, {"color", Input::Color}, {"primitiveId", Input::PrimitiveId},
        {"worldPosition", Input::WorldPosition}, {"worldNormal", Input::WorldNormal},
    }};
    const std::string name = getString("inAttribute", "attribute0");
    for (const auto& [known, input] : kNames)
        if (name == known) return input;
    reportWarning("parameter 'inAttribute' has unknown value '" + name +
                  "' (expected attribute0..3, color, primitiveId, worldPosition or worldNormal); using 'attribute0'");
    return Input::Attribute0;
}

}  // namespace ripple::device
