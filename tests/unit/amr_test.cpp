// Block-structured AMR (core/scene/AmrGrid, shaders/amr.glsl) against exact answers: at random points the
// kernels return exactly the value of the finest cell a host-side search finds, holes between blocks give
// none; one analytic field sampled at three levels differs from its finest-level sampling by at most the
// reconstruction's stated bound (half the cell-width difference times the gradient's 1-norm); a constant
// field in three levels lets exp(-sigma L) through; a fine level that repeats the coarse values gives the
// coarse level's image; inconsistent hierarchies are refused by name. Image metric: means over the pixels,
// or over blocks of them, within 1% (relative) plus 4 standard errors of the sample noise.
#include "core/scene/AmrGrid.h"
#include "shaders/test_amr_probe.spv.h"
#include "tests/support/ProbeKernel.h"
#include "tests/support/Refusal.h"
#include "tests/support/RenderHelpers.h"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <random>

using namespace ripple;

namespace {

// A block of `level` over cells lower..upper, each valued f(its centre in level units).
core::AmrBlock block(const core::AmrHierarchy& h, uint32_t level, glm::ivec3 lower, glm::ivec3 upper,
                     const std::function<float(glm::dvec3)>& f) {
    core::AmrBlock b{level, lower, upper, {}};
    for (int z = lower.z; z <= upper.z; ++z)
        for (int y = lower.y; y <= upper.y; ++y)
            for (int x = lower.x; x <= upper.x; ++x)
                b.values.push_back(f((glm::dvec3(x, y, z) + 0.5) * double(h.cellWidth[level])));
    return b;
}

// Three levels (cell widths 1, 1/2, 1/4) over level units [0, 8] x [0, 4] x [0, 4]; level 0 leaves a hole
// (x >= 4, z >= 2), level 1 refines [1, 4] x [1, 4] x [1, 3] and level 2 [1.5, 3.5] x [1.5, 2.5] x [1.5, 3].
core::AmrHierarchy threeLevels(const std::function<float(glm::dvec3)>& f, glm::vec3 origin, glm::vec3 spacing) {
    core::AmrHierarchy h;
    h.cellWidth = {1.0f, 0.5f, 0.25f};
    h.origin = origin;
    h.spacing = spacing;
    h.blocks.push_back(block(h, 0, {0, 0, 0}, {3, 3, 3}, f));
    h.blocks.push_back(block(h, 0, {4, 0, 0}, {7, 3, 1}, f));
    h.blocks.push_back(block(h, 1, {2, 2, 2}, {7, 7, 5}, f));
    h.blocks.push_back(block(h, 2, {6, 6, 6}, {13, 9, 11}, f));
    return h;
}

// The finest cell holding level-unit point u: (level, value); nullopt in no block.
std::optional<std::pair<uint32_t, float>> finestCell(const core::AmrHierarchy& h, glm::dvec3 u) {
    std::optional<std::pair<uint32_t, float>> best;
    for (const core::AmrBlock& b : h.blocks) {
        const glm::ivec3 c = glm::ivec3(glm::floor(u / double(h.cellWidth[b.level])));
        if (glm::any(glm::lessThan(c, b.lower)) || glm::any(glm::greaterThan(c, b.upper))) continue;
        if (best && best->first >= b.level) continue;
        const glm::ivec3 d = b.upper - b.lower + 1, i = c - b.lower;
        best = {b.level, b.values[size_t((i.z * d.y + i.y) * d.x + i.x)]};
    }
    return best;
}

// The field as the kernels find it at object-space points: (found, value) per point, from the probe kernel.
std::vector<glm::vec2> probe(const core::AmrGrid& grid, const std::vector<glm::vec3>& points) {
    std::vector<glm::vec4> gridPoints;
    for (const glm::vec3& p : points) gridPoints.emplace_back(glm::vec3(grid.objectToGrid * glm::dvec4(p, 1.0)), 0.0f);
    return test::runProbe(shaders::test_amr_probe, "test_amr_probe", grid.words, gridPoints, grid.macrocells);
}

// Random level-unit points in [0, 8] x [0, 4] x [0, 4], each at least 1e-3 from the finest level's cell
// faces (multiples of 1/4), where float rounding could put it in either neighbour.
std::vector<glm::dvec3> interiorPoints(uint32_t count, uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::dvec3> points;
    while (points.size() < count) {
        const glm::dvec3 u(8.0 * unit(random), 4.0 * unit(random), 4.0 * unit(random));
        const glm::dvec3 offFace = glm::abs(u * 4.0 - glm::round(u * 4.0));
        if (glm::all(glm::greaterThan(offFace, glm::dvec3(4e-3)))) points.push_back(u);
    }
    return points;
}

core::Volume amrVolume(const core::AmrHierarchy& h, float opacity1, float unitDistance, glm::vec3 albedo) {
    core::Volume v;
    v.amr = core::prepareAmrGrid(h);
    v.valueRange = {0.0f, 1.0f};
    v.colors = {albedo};
    v.opacities = {0.0f, opacity1};
    v.unitDistance = unitDistance;
    return v;
}

}  // namespace

TEST_CASE("AMR: the kernels find the finest covering cell's value at every point, and none in holes") {
    test::ValidationGuard guard;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    // Values unrelated to position, so that a wrong cell or level cannot give the right one.
    const core::AmrHierarchy h = threeLevels([&](glm::dvec3) { return unit(random); }, {-1.0f, 2.0f, 0.5f}, {0.5f, 0.25f, 2.0f});
    const auto grid = core::prepareAmrGrid(h);
    CHECK(grid->levels == 3);
    CHECK(grid->cells == 64 + 32 + 144 + 192);
    const std::vector<glm::dvec3> points = interiorPoints(4000, 5);
    std::vector<glm::vec3> objectPoints;
    for (const glm::dvec3& u : points) objectPoints.push_back(glm::vec3(glm::dvec3(h.origin) + glm::dvec3(h.spacing) * u));
    const std::vector<glm::vec2> found = probe(*grid, objectPoints);
    uint32_t wrong = 0, holes = 0, perLevel[3] = {0, 0, 0};
    for (size_t i = 0; i < points.size(); ++i) {
        const auto expected = finestCell(h, points[i]);
        if (!expected) {
            ++holes;
            wrong += found[i].x != 0.0f;
            continue;
        }
        ++perLevel[expected->first];
        if (found[i].x != 1.0f || found[i].y != expected->second) {
            if (wrong < 5) MESSAGE("point " << points[i].x << " " << points[i].y << " " << points[i].z << ": " << found[i].y << ", expected " << expected->second);
            ++wrong;
        }
    }
    CHECK(wrong == 0);
    // Every case was exercised: the hole and each level.
    CHECK(holes > 100);
    for (uint32_t count : perLevel) CHECK(count > 100);
    MESSAGE(holes << " points in the hole; " << perLevel[0] << ", " << perLevel[1] << ", " << perLevel[2] << " on levels 0, 1, 2");
}

TEST_CASE("AMR: a field sampled at three levels is within the stated bound of its finest-level sampling") {
    // Finest-cell reconstruction of cell-centre samples: at a point whose finest covering cell has width w,
    // |value - (the value of the width-1/4 cell there)| <= |grad f|_1 (w - 1/4) / 2 for a linear f, with equality
    // possible: both are f at centres at most (w - 1/4) / 2 apart per axis.
    test::ValidationGuard guard;
    const glm::dvec3 gradient(0.07, -0.05, 0.11);
    const auto f = [&](glm::dvec3 u) { return float(0.5 + glm::dot(gradient, u - glm::dvec3(4.0, 2.0, 2.0))); };
    const core::AmrHierarchy h = threeLevels(f, glm::vec3(0.0f), glm::vec3(1.0f));
    const auto grid = core::prepareAmrGrid(h);
    const std::vector<glm::dvec3> points = interiorPoints(3000, 9);
    std::vector<glm::vec3> objectPoints(points.begin(), points.end());
    const std::vector<glm::vec2> found = probe(*grid, objectPoints);
    const double gradientNorm = std::abs(gradient.x) + std::abs(gradient.y) + std::abs(gradient.z);
    double worstRatio = 0.0, largest = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        const auto cell = finestCell(h, points[i]);
        if (!cell) continue;
        REQUIRE(found[i].x == 1.0f);
        const double width = h.cellWidth[cell->first];
        const double finest = f((glm::floor(points[i] * 4.0) + 0.5) / 4.0);
        const double bound = gradientNorm * (width - 0.25) / 2.0 + 1e-6;
        const double error = std::abs(double(found[i].y) - finest);
        worstRatio = std::max(worstRatio, error / bound);
        largest = std::max(largest, error);
        CHECK(error <= bound);
    }
    MESSAGE("largest difference " << largest << ", at most " << worstRatio << " of the bound");
    // The bound is nearly reached somewhere (a coarse cell's corner), so it is not loose by construction.
    CHECK(worstRatio > 0.5);
}

TEST_CASE("AMR: a constant field in three levels lets exp(-sigma L) through, sigma 1e-3 to 1e3") {
    test::ValidationGuard guard;
    // Level units [0, 8] x [0, 4] x [0, 4] onto [-1, 1]^2 x [0, 2 / sigma] (optical depth 2; the hole's
    // columns, x > 0, are half as deep); the camera sees x in [-0.9, 0.9]. The box's aspect reaches 10^3.
    for (const float sigma : {1e-3f, 1.0f, 1e3f}) {
        const float depth = 2.0f / sigma;
        const core::AmrHierarchy h = threeLevels([](glm::dvec3) { return 1.0f; }, {-1.0f, -1.0f, 0.0f}, {0.25f, 0.5f, depth / 4.0f});
        core::RenderSettings settings;
        settings.background = glm::vec4(1.0f);
        settings.maxPathLength = 1;
        settings.pixelSamples = 64;
        core::SceneDescription scene;
        // Opacity 1 - exp(-1) over unitDistance 1 / sigma: extinction sigma.
        scene.volumes.push_back(amrVolume(h, 1.0f - std::exp(-1.0f), 1.0f / sigma, glm::vec3(0.0f)));
        const test::Rendered image = test::render(scene, test::lookingDown(depth + 1.0f, 1.8f), settings, {24, 24});
        CHECK(image.stats.flaggedRays == 0);
        // Left half: optical depth 2; right half: 1 (the hole above half the depth).
        const test::Mean left = test::meanRed(image, {0, 12, 0, 24}), right = test::meanRed(image, {12, 24, 0, 24});
        const double expectedLeft = std::exp(-2.0), expectedRight = std::exp(-1.0);
        MESSAGE("sigma " << sigma << ": " << left.mean << " +- " << left.standardError << " (expected " << expectedLeft << "), "
                         << right.mean << " +- " << right.standardError << " (expected " << expectedRight << ")");
        CHECK(std::abs(left.mean - expectedLeft) <= 0.01 * expectedLeft + 4.0 * left.standardError);
        CHECK(std::abs(right.mean - expectedRight) <= 0.01 * expectedRight + 4.0 * right.standardError);
    }
}

TEST_CASE("AMR: a fine level that repeats the coarse values gives the coarse level's image") {
    test::ValidationGuard guard;
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    core::AmrHierarchy coarse;
    coarse.cellWidth = {1.0f, 0.5f};
    coarse.origin = {-1.0f, -1.0f, 0.0f};
    coarse.spacing = glm::vec3(0.25f);
    // Each cell nearly clear or nearly opaque, at random: a high-contrast image.
    coarse.blocks.push_back(block(coarse, 0, {0, 0, 0}, {7, 7, 7}, [&](glm::dvec3) { return unit(random) < 0.5f ? 0.05f : 0.95f; }));
    // The fine level: the top half of the box over y < 5/8 of it, each cell the value of the coarse cell
    // holding it.
    const auto fineLevel = [&](const std::function<float(float)>& edit) {
        core::AmrHierarchy h = coarse;
        h.blocks.push_back(block(h, 1, {0, 0, 8}, {15, 9, 15}, [&](glm::dvec3 u) {
            const glm::ivec3 c(glm::floor(u));
            return edit(coarse.blocks[0].values[size_t((c.z * 8 + c.y) * 8 + c.x)]);
        }));
        return h;
    };
    const core::AmrHierarchy refined = fineLevel([](float v) { return v; });
    // A mutant whose fine level is dense throughout must differ (the comparison can fail).
    const core::AmrHierarchy dense = fineLevel([](float) { return 0.95f; });
    core::RenderSettings settings;
    settings.background = glm::vec4(0.0f);
    settings.maxPathLength = 4;
    settings.pixelSamples = 256;
    const core::Camera camera = test::lookingDown(3.0f, 2.2f);
    const auto image = [&](const core::AmrHierarchy& h) {
        return test::render(test::sunlitVolume(amrVolume(h, 0.6f, 0.3f, glm::vec3(0.8f))), camera, settings, {32, 32});
    };
    const test::Rendered a = image(coarse), b = image(refined), c = image(dense);
    CHECK(a.stats.flaggedRays == 0);
    CHECK(b.stats.flaggedRays == 0);
    // The refined field's image against the coarse one's.
    const double worst = test::worstBlock(b, a, 4);
    CHECK(worst <= 1.0);
    // The mutant over pixel rows 12..18, which see y in [-0.28, 0.21], under the fine level.
    const glm::uvec4 underFine(4, 28, 12, 19);
    const test::Mean ma = test::meanRed(a, underFine), mc = test::meanRed(c, underFine);
    const double mutantTolerance = 0.01 * ma.mean + 4.0 * std::hypot(ma.standardError, mc.standardError);
    MESSAGE("worst block at " << worst << " of its tolerance; the dense fine level changes the mean under it from "
                              << ma.mean << " to " << mc.mean << ", " << std::abs(mc.mean - ma.mean) / mutantTolerance
                              << " times the tolerance");
    CHECK(std::abs(ma.mean - mc.mean) > mutantTolerance);
}

TEST_CASE("AMR: inconsistent hierarchies are refused by name") {
    const auto one = [](glm::dvec3) { return 1.0f; };
    const core::AmrHierarchy good = threeLevels(one, glm::vec3(0.0f), glm::vec3(1.0f));
    const auto refusal = [](const core::AmrHierarchy& h) { return test::refusalOf([&] { core::prepareAmrGrid(h); }); };
    CHECK(refusal(good).empty());
    const auto edited = [&](const std::function<void(core::AmrHierarchy&)>& edit) {
        core::AmrHierarchy h = good;
        edit(h);
        return refusal(h);
    };
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks.clear(); }) == "the hierarchy has no block");
    CHECK(edited([](core::AmrHierarchy& h) { h.cellWidth.clear(); }) == "no cell width (one per level) is given");
    CHECK(edited([](core::AmrHierarchy& h) { h.cellWidth[1] = 1.0f; }) ==
          "the cell width of level 1 (1.000000) is not below level 0's (1.000000)");
    CHECK(edited([](core::AmrHierarchy& h) { h.cellWidth[2] = NAN; }) == "the cell width of level 2 is not finite and positive");
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks[3].level = 3; }) == "block 3 (level 3) has no cell width: 3 levels are given");
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks[2].upper.y = 1; }) == "block 2 (level 1) has an empty box [2 2 2 .. 7 1 5]");
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks[1].values.pop_back(); }) == "block 1 (level 0) has 31 values for its 4x4x2 cells");
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks[2].values[7] = INFINITY; }) == "block 2 (level 1) value 7 is not finite");
    // Overlapping blocks of one level.
    CHECK(edited([&](core::AmrHierarchy& h) { h.blocks.push_back(block(h, 1, {6, 6, 4}, {9, 7, 5}, one)); }) ==
          "block 2 (level 1) [2 2 2 .. 7 7 5] and block 4 [6 6 4 .. 9 7 5] overlap");
    // Out of the level's index space (past the coarsest level's box).
    CHECK(edited([&](core::AmrHierarchy& h) { h.blocks.push_back(block(h, 2, {30, 0, 0}, {33, 3, 3}, one)); }) ==
          "block 4 (level 2)'s box [30 0 0 .. 33 3 3] lies outside the box of level 0's blocks");
    CHECK(edited([](core::AmrHierarchy& h) { h.blocks[0].upper.x = 1 << 25; }) == "block 0 (level 0)'s box [0 0 0 .. 33554432 3 3] reaches past +-2^24");
    CHECK(edited([](core::AmrHierarchy& h) { h.spacing.y = 0.0f; }) == "the origin must be finite and the spacing finite and positive");
    // Stiff, not wrong: cell widths 10^40 apart are prepared (the macrocells coarsen in double until they fit).
    core::AmrHierarchy extreme;
    extreme.cellWidth = {1e20f, 1e-20f};
    extreme.blocks.push_back(block(extreme, 0, {0, 0, 0}, {1, 1, 1}, one));
    extreme.blocks.push_back(block(extreme, 1, {0, 0, 0}, {1, 1, 1}, one));
    CHECK(refusal(extreme).empty());
}
