// N ranks, each holding only its part of a scene, render what one rank holding everything renders: each
// exchange (ring, bounds-culled) brings every ray the globally closest hit and occlusion, lights are
// gathered, pixels are shaded at home and gathered on rank 0. Run under mpirun with 1 to 4 ranks
// (tests/mpi/CMakeLists.txt).
#include "mpi/BoundsExchange.h"
#include "mpi/Communicator.h"
#include "mpi/FrameGather.h"
#include "mpi/LightGather.h"
#include "mpi/RingExchange.h"
#include "tests/mpi/DataParallelScenes.h"
#include "tests/support/RenderHelpers.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

using namespace ripple;

namespace {

constexpr glm::uvec2 kSize{64, 64};

struct Comparison {
    uint64_t pixels = 0;
    uint64_t equal = 0;  // within kTolerance on every channel
};

// Floating point ties (two ranks' surfaces at exactly the same t) may resolve differently; anything else
// must agree to rounding: 1e-5 relative (or absolute below 1).
constexpr float kTolerance = 1e-5f;

Comparison compare(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    Comparison c;
    c.pixels = a.size();
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
        bool same = true;
        for (int k = 0; k < 4; ++k)
            same = same && std::abs(a[i][k] - b[i][k]) <= kTolerance * std::max(1.0f, std::abs(b[i][k]));
        c.equal += same;
    }
    return c;
}

using ScenePart = std::function<core::SceneDescription(uint32_t rank, uint32_t ranks)>;

std::unique_ptr<core::RayExchange> makeExchange(core::ExchangeKind kind, const mpi::Communicator& world) {
    if (kind == core::ExchangeKind::Ring) return std::make_unique<mpi::RingExchange>(world);
    return std::make_unique<mpi::BoundsExchange>(world);
}

constexpr core::ExchangeKind kExchanges[] = {core::ExchangeKind::Ring, core::ExchangeKind::Bounds};

// Renders the scene split over all ranks and, on rank 0, compares it with the whole scene rendered by
// rank 0 alone. Collective.
void checkEquivalence(const ScenePart& part, const core::Camera& camera, core::ExchangeKind kind,
                      glm::uvec2 size = kSize, uint32_t pixelSamples = 2) {
    test::ValidationGuard guard;
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), ranks = uint32_t(world.size());
    core::RenderSettings settings;
    settings.maxPathLength = 3;  // direct light, one indirect bounce and a second one
    settings.pixelSamples = pixelSamples;
    settings.background = {0.1f, 0.1f, 0.15f, 1.0f};

    core::SceneDescription mine = part(rank, ranks);
    mine.lights = mpi::gatherLights(world, mine.lights);
    // Lights are picked by power, and a directional light's counts through the whole world's bounds.
    bvh::Aabb bounds = test::worldBounds(mine);
    world.min(std::span<float>(&bounds.lo.x, 3));
    world.max(std::span<float>(&bounds.hi.x, 3));
    mine.lightSceneRadius = 0.5f * glm::length(bounds.hi - bounds.lo);
    const std::unique_ptr<core::RayExchange> exchange = makeExchange(kind, world);
    core::PathTracerOptions options;
    options.exchange = exchange.get();
    test::Rendered split = test::render(mine, camera, settings, size, true, options);
    mpi::gatherFrame(world, size, sizeof(glm::vec4), split.color.data());
    mpi::gatherFrame(world, size, sizeof(float), split.depth.data());
    const uint64_t raysSent = world.sum(exchange->stats().raysSent);
    if (ranks > 1) CHECK(raysSent > 0);
    CHECK(split.stats.flaggedRays == 0);
    if (rank != 0) return;

    core::SceneDescription all = part(0, 1);
    const bvh::Aabb allBounds = test::worldBounds(all);
    all.lightSceneRadius = 0.5f * glm::length(allBounds.hi - allBounds.lo);
    CHECK(all.lightSceneRadius == mine.lightSceneRadius);
    const test::Rendered whole = test::render(all, camera, settings, size, true);
    const Comparison c = compare(split.color, whole.color);
    MESSAGE(ranks << " ranks, " << std::string(core::exchangeKindName(kind)) << " exchange: " << c.equal << " of " << c.pixels << " pixels equal the one-rank render; rays sent "
                  << raysSent);
    CHECK(c.equal * 1000 >= c.pixels * 999);  // >= 99.9% of pixels
    uint64_t depthEqual = 0;
    for (size_t i = 0; i < whole.depth.size(); ++i) depthEqual += split.depth[i] == whole.depth[i];
    CHECK(depthEqual * 1000 >= whole.depth.size() * 999);

    // The split matters: rank 0's part alone (its own lights, no exchange) renders a clearly different
    // image, so agreement above is the exchange's doing.
    if (ranks > 1) {
        const test::Rendered alone = test::render(part(0, ranks), camera, settings, size, true);
        CHECK(compare(alone.color, whole.color).equal * 10 < c.pixels * 9);
    }
}

}  // namespace

TEST_CASE("data parallel: 4x4x4 boxes split over the ranks render as one rank holding all of them") {
    for (const core::ExchangeKind kind : kExchanges) checkEquivalence(test::boxesPart, test::boxesCamera(), kind);
}

// 100x40 pixels are ten bands of four rows: at 3 ranks 4, 3 and 3 bands, at 4 ranks 3, 3, 2 and 2. A pass
// holds as many of a pixel's samples as fit the packed paths of the busiest rank (65,536 / 1,600 = 40 at
// 3 ranks, 54 at 4), fewer than the other ranks alone would pick (54; 64), so 64 samples take two passes,
// the second of fewer samples, on every rank. Every rank must run as many passes for the exchanges to pair
// up: at 4 ranks, ranks choosing alone would run two passes on some and one on the others, and hang.
TEST_CASE("data parallel: ranks owning unequal pixel counts agree on every pass's samples") {
    checkEquivalence(test::boxesPart, test::boxesCamera(), core::ExchangeKind::Bounds, {100, 40}, 64);
}

TEST_CASE("data parallel: mixed meshes, spheres, cylinders, metal and transparency split over the ranks") {
    for (const core::ExchangeKind kind : kExchanges) checkEquivalence(test::mixedPart, test::mixedCamera(), kind);
}

TEST_CASE("data parallel: iso-surfaces of a field split into slabs over the ranks") {
    for (const core::ExchangeKind kind : kExchanges) checkEquivalence(test::isosurfacePart, test::volumeCamera(), kind);
}

TEST_CASE("data parallel: world bounds are reduced, lights gathered in rank order") {
    const mpi::Communicator world = mpi::Communicator::world();
    std::vector<core::Light> mine(size_t(world.rank()) + 1);
    for (core::Light& light : mine) light.intensity = float(world.rank());
    const std::vector<core::Light> all = mpi::gatherLights(world, mine);
    const int n = world.size();
    CHECK(all.size() == size_t(n * (n + 1) / 2));
    if (!all.empty()) CHECK(all.back().intensity == float(n - 1));
    float lo[3] = {float(world.rank()), 0.0f, -1.0f};
    world.min(lo);
    CHECK(lo[0] == 0.0f);
    float hi[1] = {float(world.rank())};
    world.max(hi);
    CHECK(hi[0] == float(n - 1));
}

// Volumes split into slabs: every rank samples free flight in its own slab, the nearest collision over the
// ranks wins, and a shadow ray carries home the product of the ranks' transmittances. The random numbers
// differ from one rank's (each rank keys its own), so the images agree statistically, not pixel by pixel:
// the image means within 3%, and 6x6-pixel tile means within 12% for 90% of the tiles (at 64 samples
// their noise is a few percent). The volume matters: the image without it fails the tile criterion.
namespace {

void checkVolumeSlabs(core::ExchangeKind kind, const core::VolumeParkingOptions& parking = {}) {
    test::ValidationGuard guard;
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), ranks = uint32_t(world.size());
    core::RenderSettings settings;
    settings.maxPathLength = 4;
    settings.pixelSamples = 64;
    settings.ambientRadiance = 0.3f;
    const glm::uvec2 size{36, 36};
    core::SceneDescription mine = test::volumePart(rank, ranks);
    mine.lights = mpi::gatherLights(world, mine.lights);
    mine.lightSceneRadius = 8.0f;
    const std::unique_ptr<core::RayExchange> exchange = makeExchange(kind, world);
    core::PathTracerOptions options;
    options.exchange = exchange.get();
    options.volumeParking = parking;
    test::Rendered split = test::render(mine, test::volumeCamera(), settings, size, false, options);
    mpi::gatherFrame(world, size, sizeof(glm::vec4), split.color.data());
    CHECK(split.stats.flaggedRays == 0);
    if (parking.stepBudget < 64) CHECK(world.sum(split.stats.parkedMarches) > 0);
    if (rank != 0) return;

    core::SceneDescription all = test::volumePart(0, 1);
    all.lightSceneRadius = 8.0f;
    const test::Rendered whole = test::render(all, test::volumeCamera(), settings, size);
    auto mean = [](const std::vector<glm::vec4>& image, uint32_t x0, uint32_t y0, uint32_t w, uint32_t width) {
        double sum = 0.0;
        for (uint32_t y = y0; y < y0 + w; ++y)
            for (uint32_t x = x0; x < x0 + w; ++x) {
                const glm::vec4& c = image[size_t(y) * width + x];
                sum += double(c.r + c.g + c.b);
            }
        return sum / double(3 * w * w);
    };
    const double splitMean = mean(split.color, 0, 0, size.x, size.x), wholeMean = mean(whole.color, 0, 0, size.x, size.x);
    MESSAGE(ranks << " ranks, " << std::string(core::exchangeKindName(kind)) << " exchange: image mean " << splitMean << ", one rank " << wholeMean);
    CHECK(std::abs(splitMean - wholeMean) <= 0.03 * wholeMean);
    auto closeTiles = [&](const std::vector<glm::vec4>& image) {
        uint32_t close = 0;
        for (uint32_t y = 0; y < size.y; y += 6)
            for (uint32_t x = 0; x < size.x; x += 6) {
                const double a = mean(image, x, y, 6, size.x), b = mean(whole.color, x, y, 6, size.x);
                close += std::abs(a - b) <= 0.12 * std::max(b, 0.02);
            }
        return close;
    };
    const uint32_t tiles = (size.x / 6) * (size.y / 6), close = closeTiles(split.color);
    MESSAGE(close << " of " << tiles << " tiles within 12%");
    CHECK(close * 10 >= tiles * 9);

    core::SceneDescription empty = test::volumePart(0, 1);
    empty.volumes.clear();
    empty.lightSceneRadius = 8.0f;
    const uint32_t closeWithout = closeTiles(test::render(empty, test::volumeCamera(), settings, size).color);
    MESSAGE("without the volume: " << closeWithout << " of " << tiles << " tiles within 12%");
    CHECK(closeWithout * 10 < tiles * 9);
}

}  // namespace

TEST_CASE("data parallel: a scattering volume split into slabs over the ranks renders as on one rank") {
    for (const core::ExchangeKind kind : kExchanges) checkVolumeSlabs(kind);
}

// The same with every march parked every few steps and resumed, the visiting rays' marches included.
TEST_CASE("data parallel: volume marches parked and resumed on every rank still render as on one rank") {
    checkVolumeSlabs(core::ExchangeKind::Bounds, {.stepBudget = 8, .resumeRounds = gpu::VOLUME_MAX_RESUME_ROUNDS});
}
