// ANARI sampler: turns a surface attribute into a colour. Ripple's one subtype, image2D, becomes a
// core::Texture that materials reference.
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/scene/SceneDescription.h"

namespace ripple::device {

class Sampler : public SceneObject {
public:
    Sampler(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_SAMPLER, std::move(subtype)) {}
    // The committed texture; nullptr when nothing valid was committed.
    virtual const core::Texture* texture() const = 0;
};

Sampler* newImage2DSampler(DeviceState& state);

}  // namespace ripple::device
