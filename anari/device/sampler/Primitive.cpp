// Sampler subtype "primitive" (KHR_SAMPLER_PRIMITIVE): entry (primitive id + inOffset) of an array, a
// value per primitive. Ids past the end read the last entry.
#include "anari/device/sampler/Sampler.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

namespace ripple::device {
namespace {

class PrimitiveSampler final : public Sampler {
public:
    explicit PrimitiveSampler(DeviceState& state) : Sampler(state, "primitive") {}

    void commit() override {
        forgetDependencies();
        texture_.reset();
        Array* array = getArray("array", ANARI_ARRAY1D);
        if (!array) {
            invalidate(has("array") ? "parameter 'array' must be an ARRAY1D" : "missing required parameter 'array'");
            return;
        }
        useArray(array);
        if (array->size() == 0 || array->size() > std::numeric_limits<uint32_t>::max()) {
            invalidate("parameter 'array' must have between 1 and 2^32 - 1 entries");
            return;
        }
        const std::optional<std::vector<glm::vec4>> values = readFloatVectors(*array, glm::vec4(0, 0, 0, 1));
        if (!values) {
            invalidate(elementTypeProblem("array", array->elementType(), "numbers (e.g. FLOAT32_VEC4)"));
            return;
        }
        if (reject(nonFiniteProblem("array", *values, "entry"))) return;
        core::Texture texture;
        texture.kind = core::Texture::Kind::Primitive;
        texture.input = core::Texture::Input::PrimitiveId;
        texture.width = uint32_t(values->size());
        texture.height = 1;
        texture.format = core::Texture::Format::Rgba32Float;
        texture.linearFilter = false;
        texture.texels.resize(values->size() * sizeof(glm::vec4));
        std::memcpy(texture.texels.data(), values->data(), texture.texels.size());
        // Offsets past the array all read its last entry, so clamping to 32 bits changes nothing.
        texture.primitiveOffset = uint32_t(std::min<uint64_t>(get<uint64_t>("inOffset", 0), texture.width));
        texture_ = std::move(texture);
    }
};

}  // namespace

Sampler* newPrimitiveSampler(DeviceState& state) { return new PrimitiveSampler(state); }

}  // namespace ripple::device
