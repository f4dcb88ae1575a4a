// NanoVDB grids (core/scene/NanoVdbGrid, shaders/nanovdb.glsl): a fog sphere made with NanoVDB's own tools, and
// one made with OpenVDB's (a level-set sphere turned into a fog volume), renders as the same values copied into
// a dense structuredRegular grid (the means of 8x8 blocks of 4x4 pixels within 1% plus 4 standard errors of the
// sample noise; the grid moved by 3 voxels fails it); rays
// between two balls, through macrocells that hold no active voxel, make no tentative collision at all;
// corrupt buffers are refused by name before any kernel reads them.
#include "core/scene/NanoVdbGrid.h"
#include "tests/support/Refusal.h"
#include "tests/support/RenderHelpers.h"

#include <doctest/doctest.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <nanovdb/util/Primitives.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

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

// The same made with OpenVDB's own tools: a level-set sphere turned into a fog volume (1 inside, falling to 0
// across the narrow band inside the surface), converted with NanoVDB's converter.
nanovdb::GridHandle<nanovdb::HostBuffer> openVdbFogSphere() {
    openvdb::initialize();
    openvdb::FloatGrid::Ptr fog = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.05f);
    openvdb::tools::sdfToFogVolume(*fog);
    return nanovdb::openToNanoVDB(*fog);
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

TEST_CASE("NanoVDB: a fog sphere (NanoVDB's tools, and OpenVDB's) renders as the same values on a dense structuredRegular grid") {
    for (const bool madeByOpenVdb : {false, true}) {
        CAPTURE(madeByOpenVdb);
        test::ValidationGuard guard;
        const auto handle = madeByOpenVdb ? openVdbFogSphere() : fogSphere();
        const auto grid = core::prepareNanoVdbGrid(bytesOf(handle));
        CHECK(grid->valueRange.x >= 0.0f);
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
        const double worst = test::worstBlock(a, b, 4);
        CHECK(worst <= 1.0);
        MESSAGE((madeByOpenVdb ? "OpenVDB" : "NanoVDB") << "'s sphere: worst block at " << worst << " of its tolerance; "
                                                         << grid->leaves << " leaves, macrocells " << grid->macrocells.x << "x"
                                                         << grid->macrocells.y << "x" << grid->macrocells.z);
    }
}

TEST_CASE("NanoVDB: rays between two spheres, through macrocells with no active voxel, make no tentative collision") {
    // Two fog balls of radius 10 voxels (0.5) at x = -20 and x = +20 voxels (NanoVDB's GridBuilder): 1 deep
    // inside, falling to 0 over the 3 voxels inside the surface; no voxel is active outside them. The field's
    // box runs from voxel -30 to 30, so macrocell 3 along x reads voxels -6 to 2, all background (0): the
    // column of rays over x in [-0.25, 0.05] crosses only macrocells whose majorant is 0, and collides nowhere.
    test::ValidationGuard guard;
    nanovdb::GridBuilder<float> builder(0.0f);
    auto voxels = builder.getAccessor();
    for (const int centre : {-20, 20})
        for (int z = -10; z <= 10; ++z)
            for (int y = -10; y <= 10; ++y)
                for (int x = -10; x <= 10; ++x) {
                    const float r = std::sqrt(float(x * x + y * y + z * z));
                    if (r <= 10.0f) voxels.setValue(nanovdb::Coord(centre + x, y, z), std::min(1.0f, (10.0f - r) / 3.0f));
                }
    const auto handle = builder.getHandle(0.05);
    core::Volume sparse;
    sparse.nanovdb = core::prepareNanoVdbGrid(bytesOf(handle));
    REQUIRE(sparse.nanovdb->base.x == -30);
    core::Camera camera = test::lookingDown(3.0f, 0.3f);
    camera.position = glm::vec3(-0.1f, 0.0f, 3.0f);
    const test::Rendered between = litImage(mediumOf(sparse), camera, {16, 16});
    CHECK(between.stats.nullCollisions == 0);
    CHECK(between.stats.realCollisions == 0);
    // Over a ball's centre the same volume does collide (the count can fail).
    camera.position = glm::vec3(1.0f, 0.0f, 3.0f);
    const test::Rendered ball = litImage(mediumOf(sparse), camera, {16, 16});
    CHECK(ball.stats.realCollisions > 0);
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
