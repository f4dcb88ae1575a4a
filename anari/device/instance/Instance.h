// ANARI instance: places a group in the world. Ripple's one subtype, "transform", places it with an
// affine matrix that applies to the group's surfaces and lights alike.
#pragma once

#include "anari/device/group/Group.h"

#include <array>
#include <optional>

namespace ripple::device {

class Instance : public SceneObject {
public:
    Instance(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_INSTANCE, std::move(subtype)) {}

    Group* group() const { return group_; }
    const glm::mat4& transform() const { return transform_; }
    // The application's "id" (instanceId channel), if it gave one.
    std::optional<uint32_t> id() const { return id_; }
    // The uniform "color" and "attribute0".."attribute3", where set: on this instance they replace the
    // values its geometries give.
    const std::optional<glm::vec4>& color() const { return color_; }
    const std::array<std::optional<glm::vec4>, 4>& attributes() const { return attributes_; }

protected:
    Group* group_ = nullptr;  // kept alive by useChild()
    glm::mat4 transform_{1.0f};
    std::optional<uint32_t> id_;
    std::optional<glm::vec4> color_;
    std::array<std::optional<glm::vec4>, 4> attributes_;
};

Instance* newTransformInstance(DeviceState& state);

}  // namespace ripple::device
