// core::Texture kinds (image 1D/2D/3D, transform, primitive) as buildShadingTables validates and records
// them: the record fields the kernels read, and exact counts of textures rejected for bad sizes.
#include "core/scene/ShadingTables.h"

#include <doctest/doctest.h>

using ripple::core::SceneDescription;
using ripple::core::Texture;

namespace {

Texture rgba8(uint32_t width, uint32_t height, uint32_t depth) {
    Texture t;
    t.width = width;
    t.height = height;
    t.depth = depth;
    t.texels.assign(size_t(width) * height * depth * 4, 255);
    return t;
}

}  // namespace

TEST_CASE("sampler kinds: records carry kind, input, depth, offsets; bad sizes are skipped and counted") {
    SceneDescription d;
    Texture volume = rgba8(2, 3, 4);
    volume.input = Texture::Input::Attribute2;
    volume.wrapR = Texture::Wrap::MirrorRepeat;
    volume.inOffset = glm::vec4(0, 0, 0.5f, 0);
    d.textures.push_back(volume);                         // 0: a valid 3D image
    Texture transform;
    transform.kind = Texture::Kind::Transform;
    transform.input = Texture::Input::Color;
    transform.outOffset = glm::vec4(1, 2, 3, 4);
    d.textures.push_back(transform);                      // 1: a valid transform (no texels)
    Texture primitive = rgba8(5, 1, 1);
    primitive.kind = Texture::Kind::Primitive;
    primitive.input = Texture::Input::PrimitiveId;
    primitive.primitiveOffset = 3;
    d.textures.push_back(primitive);                      // 2: a valid primitive array
    Texture transformWithTexels = rgba8(1, 1, 1);
    transformWithTexels.kind = Texture::Kind::Transform;
    d.textures.push_back(transformWithTexels);            // 3: a transform has no image
    Texture primitiveRows = rgba8(2, 2, 1);
    primitiveRows.kind = Texture::Kind::Primitive;
    d.textures.push_back(primitiveRows);                  // 4: a primitive array is one row
    Texture shortVolume = rgba8(2, 2, 2);
    shortVolume.texels.resize(shortVolume.texels.size() - 4);
    d.textures.push_back(shortVolume);                    // 5: one texel short of 2x2x2
    Texture unknownKind = rgba8(1, 1, 1);
    unknownKind.kind = static_cast<Texture::Kind>(7);
    d.textures.push_back(unknownKind);                    // 6: no such kind

    const ripple::core::ShadingTables tables = ripple::core::buildShadingTables(d);
    REQUIRE(tables.textures.size() == 7);
    CHECK(tables.texturesSkipped == 4);
    const auto& v = tables.textures[0];
    CHECK(v.kind == ripple::gpu::TEXTURE_KIND_IMAGE);
    CHECK(v.inputAttribute == ripple::gpu::TEXTURE_INPUT_ATTRIBUTE0 + 2);
    CHECK(v.width == 2);
    CHECK(v.height == 3);
    CHECK(v.depth == 4);
    CHECK(v.wrapR == ripple::gpu::WRAP_MIRROR_REPEAT);
    CHECK(v.inOffset.z == 0.5f);
    const auto& t = tables.textures[1];
    CHECK(t.kind == ripple::gpu::TEXTURE_KIND_TRANSFORM);
    CHECK(t.inputAttribute == ripple::gpu::TEXTURE_INPUT_COLOR);
    CHECK(t.outOffset == glm::vec4(1, 2, 3, 4));
    const auto& p = tables.textures[2];
    CHECK(p.kind == ripple::gpu::TEXTURE_KIND_PRIMITIVE);
    CHECK(p.primitiveOffset == 3);
    CHECK(p.width == 5);
    // The valid ones' texels follow each other: 24 words of the volume, then 5 of the array.
    CHECK(t.texelOffset == v.texelOffset + 24);
    CHECK(p.texelOffset == v.texelOffset + 24);
}
