// NanoVDB grids (core/scene/NanoVdbGrid, shaders/nanovdb.glsl): a fog sphere made with NanoVDB's own tools
// renders as the same values copied into a dense structuredRegular grid (the means of 8x8 blocks of 4x4
// pixels within 1% plus 4 standard errors of the sample noise; the grid moved by 3 voxels fails it); rays through a corner of its box that holds no active voxel make
// no tentative collision at all; corrupt buffers are refused by name before any kernel reads them.
#include "core/scene/NanoVdbGrid.h"
#include "tests/support/Refusal.h"
#include "tests/support/RenderHelpers.h"

#include <doctest/doctest.h>
#include <nanovdb/util/Primitives.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

using namespace ripple;

namespace {

// A fog sphere of radius 1 (20 voxels of 0.05) at the origin: 1 deep inside, falling to 0 over the 3 voxels
// inside its surface, background 0.
nanovdb::GridHandle<nanovdb::HostBuffer> fogSphere() {
    return nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f(0.0f), 0.05, 3.0);
}

std::span<const uint8_t> bytesOf(const nanovdb::GridHandle<nanovdb::HostBuffer>& handle) {
    return {handle.data(), handle.size()};
}

core::Volume mediumOf(core::Volume v) {
    v.valueRange = {0.0f, 1.0f};
    v.colors = {glm::vec3(0.8f)};
    v.opacities = {0.0f, 0.3f};
    v.unitDistance = 0.5f;
    return v;
}

test::Rendered litImage(const core::Volume& volume, const core::Camera& camera, glm::uvec2 size) {
    core::RenderSettings settings;
    settings.background = glm::vec4(0.0f);
    settings.maxPathLength = 4;
    settings.pixelSamples = 256;
    return test::render(test::sunlitVolume(volume), camera, settings, size);
}

}  // namespace

TEST_CASE("NanoVDB: a fog sphere renders as the same values on a dense structuredRegular grid") {
    test::ValidationGuard guard;
    const auto handle = fogSphere();
    const auto grid = core::prepareNanoVdbGrid(bytesOf(handle));
    CHECK(grid->valueRange.x == 0.0f);
    CHECK(grid->valueRange.y == doctest::Approx(1.0f));
    // The dense copy: every voxel of the active box, read through NanoVDB's own accessor.
    const auto* nano = handle.grid<float>();
    const nanovdb::CoordBBox box = nano->indexBBox();
    const glm::uvec3 dims(box.dim()[0], box.dim()[1], box.dim()[2]);
    auto values = std::make_shared<std::vector<float>>();
    const auto accessor = nano->getAccessor();
    for (int z = box.min()[2]; z <= box.max()[2]; ++z)
        for (int y = box.min()[1]; y <= box.max()[1]; ++y)
            for (int x = box.min()[0]; x <= box.max()[0]; ++x) values->push_back(accessor.getValue(nanovdb::Coord(x, y, z)));
    core::Volume dense;
    dense.dims = dims;
    dense.values = values;
    dense.origin = glm::vec3(box.min()[0], box.min()[1], box.min()[2]) * 0.05f;
    dense.spacing = glm::vec3(0.05f);
    core::Volume sparse;
    sparse.nanovdb = grid;
    const core::Camera camera = test::lookingDown(3.0f, 2.4f);
    const test::Rendered a = litImage(mediumOf(sparse), camera, {32, 32}), b = litImage(mediumOf(dense), camera, {32, 32});
    CHECK(a.stats.flaggedRays == 0);
    double worst = 0.0;
    for (uint32_t by = 0; by < 8; ++by)
        for (uint32_t bx = 0; bx < 8; ++bx) {
            const glm::uvec4 block(bx * 4, bx * 4 + 4, by * 4, by * 4 + 4);
            const test::Mean ma = test::meanRed(a, block), mb = test::meanRed(b, block);
            const double tolerance = 0.01 * mb.mean + 4.0 * std::hypot(ma.standardError, mb.standardError);
            worst = std::max(worst, std::abs(ma.mean - mb.mean) / tolerance);
            CAPTURE(bx);
            CAPTURE(by);
            CHECK(std::abs(ma.mean - mb.mean) <= tolerance);
        }
    MESSAGE("worst block at " << worst << " of its tolerance; " << grid->leaves << " leaves, macrocells "
                              << grid->macrocells.x << "x" << grid->macrocells.y << "x" << grid->macrocells.z);
}

TEST_CASE("NanoVDB: rays through a corner of the box with no active voxel make no tentative collision") {
    // The sphere's box runs to 20 voxels (1.0) from its centre; the column over x, y in [0.85, 1.15] holds
    // no voxel within 20 voxels of the centre, so its macrocells' majorants are 0 and no ray collides there.
    // The dense copy of the whole box, whose macrocells span more, is no reference here: the count is exact.
    test::ValidationGuard guard;
    const auto handle = fogSphere();
    core::Volume sparse;
    sparse.nanovdb = core::prepareNanoVdbGrid(bytesOf(handle));
    core::Camera camera = test::lookingDown(3.0f, 0.3f);
    camera.position = glm::vec3(1.0f, 1.0f, 3.0f);
    const test::Rendered corner = litImage(mediumOf(sparse), camera, {16, 16});
    CHECK(corner.stats.nullCollisions == 0);
    CHECK(corner.stats.realCollisions == 0);
    // Over the centre the same volume does collide (the count can fail).
    camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
    const test::Rendered centre = litImage(mediumOf(sparse), camera, {16, 16});
    CHECK(centre.stats.realCollisions > 0);
}

TEST_CASE("NanoVDB: corrupt buffers are refused by name") {
    const auto handle = fogSphere();
    const std::vector<uint8_t> good(handle.data(), handle.data() + handle.size());
    const auto refusal = [](const std::vector<uint8_t>& blob) {
        return test::refusalOf([&] { core::prepareNanoVdbGrid(blob); });
    };
    CHECK(refusal(good).empty());
    CHECK(refusal(std::vector<uint8_t>(good.begin(), good.begin() + 100)).find("too short") != std::string::npos);
    // Edits of the buffer, made in memory aligned as NanoVDB's structures need.
    struct alignas(32) Block {
        uint8_t bytes[32];
    };
    const auto edited = [&](auto edit) {
        std::vector<Block> aligned((good.size() + 31) / 32);
        std::memcpy(aligned.data(), good.data(), good.size());
        edit(reinterpret_cast<nanovdb::NanoGrid<float>*>(aligned.data()));
        std::vector<uint8_t> out(good.size());
        std::memcpy(out.data(), aligned.data(), good.size());
        return out;
    };
    CHECK(refusal(edited([](nanovdb::NanoGrid<float>* g) { reinterpret_cast<nanovdb::GridData*>(g)->mMagic ^= 0xFF; })) ==
          "not a NanoVDB grid (its magic number is wrong)");
    CHECK(refusal(std::vector<uint8_t>(good.begin(), good.begin() + std::ptrdiff_t(good.size() / 2))).find("the grid says it is") == 0);
    CHECK(refusal(edited([](nanovdb::NanoGrid<float>* g) {
              reinterpret_cast<nanovdb::GridData*>(g)->mGridType = nanovdb::GridType::Double;
          })) == "a grid of double; Ripple reads float grids");
    // A root tile's child offset sent past the buffer.
    bool corrupted = false;
    const std::vector<uint8_t> farChild = edited([&](nanovdb::NanoGrid<float>* g) {
        auto* root = g->tree().root().data();
        for (uint32_t t = 0; t < root->mTableSize && !corrupted; ++t)
            if (root->tile(t)->isChild()) {
                root->tile(t)->child = int64_t(1) << 40;
                corrupted = true;
            }
    });
    REQUIRE(corrupted);
    CHECK(refusal(farChild).find("child lies outside the grid") != std::string::npos);
    // A voxel value that is not finite.
    CHECK(refusal(edited([](nanovdb::NanoGrid<float>* g) {
              const_cast<nanovdb::NanoLeaf<float>*>(g->tree().getFirstNode<0>())->data()->mValues[5] = NAN;
          })) == "a voxel value is not finite");
}
