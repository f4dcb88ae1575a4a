// ANARI spatial fields: what a volume (Volume.h) draws through its transfer function. Subtypes
// "structuredRegular" (StructuredRegularField.h), "unstructured" (UnstructuredField.h), "nanovdb"
// (NanoVdbField.h) and "amr" (AmrField.h).
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/bvh/Aabb.h"
#include "core/scene/SceneDescription.h"

namespace ripple::device {

class SpatialField : public SceneObject {
public:
    SpatialField(DeviceState& state, const char* subtype) : SceneObject(state, ANARI_SPATIAL_FIELD, subtype) {}

    // Object-space box the field spans; empty when the field is not valid.
    virtual bvh::Aabb bounds() const = 0;
    // Sets the field's part of `volume` (its samples, or its mesh, and their identity).
    virtual void describe(core::Volume& volume) const = 0;

protected:
    // Parameter "filter": true for "linear" (the default), false for "nearest"; any other value is reported
    // and read as "linear".
    bool linearFilterParameter();
};

}  // namespace ripple::device
