// ANARI sampler: turns a surface attribute into a colour. Each subtype becomes a core::Texture that
// materials reference: image1D/2D/3D (Image.cpp), transform (Transform.cpp), primitive (Primitive.cpp).
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/scene/SceneDescription.h"

#include <optional>

namespace ripple::device {

class Sampler : public SceneObject {
public:
    Sampler(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_SAMPLER, std::move(subtype)) {}
    // The committed texture; nullptr when nothing valid was committed.
    const core::Texture* texture() const { return texture_ ? &*texture_ : nullptr; }

protected:
    // "inAttribute" (default attribute0) as a core input; an unknown name is reported, attribute0 used.
    core::Texture::Input pullInAttribute();

    std::optional<core::Texture> texture_;
};

// The surface value an ANARI attribute name stands for (attribute0..3, color, primitiveId, worldPosition,
// worldNormal), as samplers' inAttribute and material parameters given as strings name them.
std::optional<core::Texture::Input> surfaceInputNamed(std::string_view name);

// image1D, image2D or image3D (dimensions 1, 2 or 3).
Sampler* newImageSampler(DeviceState& state, int dimensions);
Sampler* newTransformSampler(DeviceState& state);
Sampler* newPrimitiveSampler(DeviceState& state);

}  // namespace ripple::device
