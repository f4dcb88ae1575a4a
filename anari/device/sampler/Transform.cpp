// Sampler subtype "transform" (KHR_SAMPLER_TRANSFORM): no image, the output is outTransform * input +
// outOffset, so any surface attribute can drive a material parameter.
#include "anari/device/sampler/Sampler.h"

#include "anari/device/object/ArrayChecks.h"

namespace ripple::device {
namespace {

class TransformSampler final : public Sampler {
public:
    explicit TransformSampler(DeviceState& state) : Sampler(state, "transform") {}

    void commit() override {
        forgetDependencies();
        texture_.reset();
        core::Texture texture;
        texture.kind = core::Texture::Kind::Transform;
        texture.input = pullInAttribute();
        texture.outTransform = get<glm::mat4>("outTransform", glm::mat4(1.0f));
        texture.outOffset = get<glm::vec4>("outOffset", glm::vec4(0.0f));
        if (reject(nonFiniteProblem("outTransform", texture.outTransform)) ||
            reject(nonFiniteProblem("outOffset", texture.outOffset)))
            return;
        texture_ = std::move(texture);
    }
};

}  // namespace

Sampler* newTransformSampler(DeviceState& state) { return new TransformSampler(state); }

}  // namespace ripple::device
