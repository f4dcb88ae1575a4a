// ANARI sampler: turns a surface attribute into a colour. Each subtype becomes a core::Texture that
// materials reference. image3D is not supported (core has no 3D textures): the factory reports it unknown.
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

// image1D (dimensions 1) or image2D (2).
Sampler* newImageSampler(DeviceState& state, int dimensions);

}  // namespace ripple::device
