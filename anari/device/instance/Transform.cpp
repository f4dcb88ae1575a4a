// Instance subtype "transform" (KHR_INSTANCE_TRANSFORM): "group" (required) placed by "transform", a
// column-major FLOAT32_MAT4 that must be affine and invertible; the uniform "color" and "attribute0..3"
// replace its geometries' own on this instance.
#include "anari/device/instance/Instance.h"

#include "anari/device/object/ArrayChecks.h"

#include <cmath>

namespace ripple::device {
namespace {

class TransformInstance final : public Instance {
public:
    explicit TransformInstance(DeviceState& state) : Instance(state, "transform") {}

    void commit() override {
        forgetDependencies();
        group_ = dynamic_cast<Group*>(getObject("group", ANARI_GROUP));
        useChild(group_);
        id_ = getOptional<uint32_t>("id");
        transform_ = get<glm::mat4>("transform", glm::mat4(1.0f));
        color_ = getOptional<glm::vec4>("color");
        for (size_t a = 0; a < attributes_.size(); ++a) attributes_[a] = getOptional<glm::vec4>("attribute" + std::to_string(a));
        if (!group_) {
            invalidate("missing required parameter 'group'");
            return;
        }
        if (std::optional<std::string> problem = nonFiniteProblem("transform", transform_)) {
            invalidate(*problem);
            return;
        }
        for (size_t u = 0; u < 5; ++u) {
            const std::string name = u == 0 ? "color" : "attribute" + std::to_string(u - 1);
            const std::optional<glm::vec4>& value = u == 0 ? color_ : attributes_[u - 1];
            if (!value) continue;
            if (std::optional<std::string> problem = nonFiniteProblem(name, *value)) {
                invalidate(*problem);
                return;
            }
        }
        const glm::vec4 lastRow(transform_[0][3], transform_[1][3], transform_[2][3], transform_[3][3]);
        const float determinant = glm::determinant(glm::mat3(transform_));
        if (lastRow != glm::vec4(0, 0, 0, 1) || !(std::abs(determinant) > 0.0f) || !std::isfinite(determinant))
            invalidate("parameter 'transform' must be an affine, invertible matrix");
    }
};

}  // namespace

Instance* newTransformInstance(DeviceState& state) {
    return new TransformInstance(state);
}

}  // namespace ripple::device
