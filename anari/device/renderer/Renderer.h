// ANARI renderers: "default", the path tracer's settings (background, ambient light, samples per frame,
// path length), and "eyeLight", a quick look at the first surfaces under a light at the eye
// (RenderSettings::Shading).
#pragma once

#include "anari/device/object/Object.h"
#include "core/render/PathTracer.h"

namespace ripple::device {

class Renderer final : public Object {
public:
    Renderer(DeviceState& state, std::string subtype) : Object(state, ANARI_RENDERER, std::move(subtype)) {}

    void commit() override;
    const core::RenderSettings& settings() const { return settings_; }
    // Whether the application set "ambientRadiance" (to any value, 0 included): if not, a world with no
    // light and no emitter gets the implicit ambient light (Frame.cpp).
    bool ambientGiven() const { return ambientGiven_; }

private:
    // pixelSamples and maxPathLength are Ripple's own; INT32 (as other devices take them) or UINT32.
    uint32_t pullCount(std::string_view name, uint32_t fallback, uint32_t most);

    core::RenderSettings settings_;
    bool ambientGiven_ = false;
};

}  // namespace ripple::device
