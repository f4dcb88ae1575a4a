// Sampler subtypes "image1D", "image2D" and "image3D" (KHR_SAMPLER_IMAGE1D/2D/3D): an image read at a
// surface attribute (inAttribute), with filter, per-axis wrap modes and input/output transforms. A 1D
// image is a core texture one row high and a 2D one a single slice, so only the first one or two
// components of the transformed input matter.
#include "anari/device/sampler/Sampler.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <cstring>
#include <optional>
#include <string>
#include <utility>

namespace ripple::device {
namespace {

core::Texture::Wrap wrapMode(const std::string& name) {
    if (name == "repeat") return core::Texture::Wrap::Repeat;
    if (name == "mirrorRepeat") return core::Texture::Wrap::MirrorRepeat;
    return core::Texture::Wrap::ClampToEdge;
}

class ImageSampler final : public Sampler {
public:
    ImageSampler(DeviceState& state, int dimensions)
        : Sampler(state, "image" + std::to_string(dimensions) + "D"), dimensions_(dimensions) {}

    void commit() override {
        forgetDependencies();
        texture_.reset();
        const ANARIDataType arrayType = dimensions_ == 1 ? ANARI_ARRAY1D : dimensions_ == 2 ? ANARI_ARRAY2D : ANARI_ARRAY3D;
        Array* image = getArray("image", arrayType);
        if (!image) {
            invalidate(has("image") ? "parameter 'image' must be an " + std::string(ripple_anari::typeName(arrayType))
                                    : "missing required parameter 'image'");
            return;
        }
        useArray(image);
        core::Texture texture;
        texture.width = uint32_t(image->dim(0));
        texture.height = dimensions_ == 1 ? 1u : uint32_t(image->dim(1));
        texture.depth = dimensions_ == 3 ? uint32_t(image->dim(2)) : 1u;
        if (texture.width == 0 || texture.height == 0 || texture.depth == 0) {
            invalidate("parameter 'image' is empty");
            return;
        }
        if (!convertTexels(*image, texture)) return;

        texture.input = pullInAttribute();
        const std::string filter = getString("filter", "linear");
        if (filter != "linear" && filter != "nearest")
            reportWarning("parameter 'filter' has unknown value '" + filter + "'; using 'linear'");
        texture.linearFilter = filter != "nearest";
        // image1D's is "wrapMode" (KHR_SAMPLER_IMAGE1D); image2D and image3D number theirs. An image1D given
        // "wrapMode1" instead (the SDK's own test scenes name it so) is read too.
        const bool legacy1D = dimensions_ == 1 && !has("wrapMode") && has("wrapMode1");
        texture.wrapS = wrapMode(checkedWrapMode(dimensions_ == 1 && !legacy1D ? "wrapMode" : "wrapMode1"));
        texture.wrapT = dimensions_ == 1 ? core::Texture::Wrap::ClampToEdge : wrapMode(checkedWrapMode("wrapMode2"));
        texture.wrapR = dimensions_ == 3 ? wrapMode(checkedWrapMode("wrapMode3")) : core::Texture::Wrap::ClampToEdge;
        texture.inTransform = get<glm::mat4>("inTransform", glm::mat4(1.0f));
        texture.inOffset = get<glm::vec4>("inOffset", glm::vec4(0.0f));
        texture.outTransform = get<glm::mat4>("outTransform", glm::mat4(1.0f));
        texture.outOffset = get<glm::vec4>("outOffset", glm::vec4(0.0f));
        if (reject(nonFiniteProblem("inTransform", texture.inTransform)) ||
            reject(nonFiniteProblem("inOffset", texture.inOffset)) ||
            reject(nonFiniteProblem("outTransform", texture.outTransform)) ||
            reject(nonFiniteProblem("outOffset", texture.outOffset)))
            return;
        texture_ = std::move(texture);
    }

private:
    std::string checkedWrapMode(std::string_view name) {
        const std::string mode = getString(name, "clampToEdge");
        if (mode != "clampToEdge" && mode != "repeat" && mode != "mirrorRepeat")
            reportWarning("parameter '" + std::string(name) + "' has unknown value '" + mode +
                          "'; using 'clampToEdge'");
        return mode;
    }

    // 8-bit images stay 8-bit (RGBA, sRGB decoded by the sampler when so typed); everything else becomes
    // RGBA float. Missing components are (0, 0, 1) for green, blue and alpha.
    bool convertTexels(const Array& image, core::Texture& texture) {
        const ANARIDataType type = image.elementType();
        const int components = componentCount(type);
        const bool srgb = type >= ANARI_UFIXED8_R_SRGB && type <= ANARI_UFIXED8_RGBA_SRGB;
        if (components == 0) {
            invalidate(elementTypeProblem("image", type,
                                          "numbers (e.g. UFIXED8_VEC4, UFIXED8_RGBA_SRGB or FLOAT32_VEC4)"));
            return false;
        }
        const size_t texelCount = image.size();
        if (srgb || (type >= ANARI_UFIXED8 && type <= ANARI_UFIXED8_VEC4)) {
            texture.format = srgb ? core::Texture::Format::Rgba8Srgb : core::Texture::Format::Rgba8Unorm;
            texture.texels.assign(texelCount * 4, 0);
            const auto* source = static_cast<const uint8_t*>(image.data());
            for (size_t i = 0; i < texelCount; ++i) {
                uint8_t* texel = &texture.texels[i * 4];
                std::memcpy(texel, source + i * components, size_t(components));
                if (type == ANARI_UFIXED8_RA_SRGB)
                    std::swap(texel[1], texel[3]);  // red and alpha
                else if (components < 4)
                    texel[3] = 255;
            }
            return true;
        }
        const std::vector<glm::vec4> values = *readFloatVectors(image, glm::vec4(0, 0, 0, 1));
        if (reject(nonFiniteProblem("image", values, "texel"))) return false;
        texture.format = core::Texture::Format::Rgba32Float;
        texture.texels.resize(texelCount * sizeof(glm::vec4));
        std::memcpy(texture.texels.data(), values.data(), texture.texels.size());
        return true;
    }

    int dimensions_;
};

}  // namespace

Sampler* newImageSampler(DeviceState& state, int dimensions) {
    return new ImageSampler(state, dimensions);
}

}  // namespace ripple::device
