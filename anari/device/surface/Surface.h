// ANARI surface: a geometry with the material it is shaded with; the unit SceneSync turns into one
// core instance per placement.
#pragma once

#include "anari/device/geometry/Geometry.h"
#include "anari/device/material/Material.h"

#include <optional>

namespace ripple::device {

class Surface final : public SceneObject {
public:
    explicit Surface(DeviceState& state) : SceneObject(state, ANARI_SURFACE, "") {}

    void commit() override;
    Geometry* geometry() const { return geometry_; }
    Material* material() const { return material_; }
    // The application's "id" (objectId channel), if it gave one.
    std::optional<uint32_t> id() const { return id_; }
    // Committed valid, visible, and its geometry and material valid now (they may be recommitted later).
    bool renderable() const;

private:
    Geometry* geometry_ = nullptr;  // kept alive by useChild()
    Material* material_ = nullptr;
    bool visible_ = true;
    std::optional<uint32_t> id_;
};

}  // namespace ripple::device
