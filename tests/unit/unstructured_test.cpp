// Unstructured volumes (core/scene/UnstructuredGrid, shaders/unstructured.glsl) against analytic answers: a
// box cut into tetrahedra, hexahedra, wedges and pyramids with a constant field lets exp(-sigma L) through,
// at extinctions 1e-6 to 1e6 (the box's aspect ratio then reaches 10^6); a linear field (the ramp of
// volume_test.cpp) is interpolated exactly by every cell shape; the same nodal field on hexahedra and as a
// structuredRegular grid gives the same image; degenerate and inverted cells are reported and never give a
// NaN or a hole; broken meshes are refused by name. Metric: the mean over the pixels (or over blocks of
// them), within 1% (relative) plus 4 standard errors of the sample noise.
#include "core/render/PathTracer.h"
#include "core/scene/UnstructuredGrid.h"
#include "shaders/shared/volume.h"
#include "shaders/test_unstructured_probe.spv.h"
#include "tests/support/ProbeKernel.h"
#include "tests/support/Refusal.h"
#include "tests/support/RenderHelpers.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <optional>
#include <stdexcept>

using namespace ripple;

namespace {

enum class Shape { Tetrahedra, Hexahedra, Wedges, Pyramids };
const char* nameOf(Shape s) {
    return s == Shape::Tetrahedra ? "tetrahedra" : s == Shape::Hexahedra ? "hexahedra" : s == Shape::Wedges ? "wedges" : "pyramids";
}

// The box [-1, 1]^2 x [0, depth] as n^3 hexahedra, each cut into `shape` cells with VTK's orientation;
// values f(position) per vertex.
template <class F>
core::UnstructuredCells boxMesh(Shape shape, uint32_t n, float depth, F f) {
    core::UnstructuredCells mesh;
    const auto vertexAt = [&](uint32_t i, uint32_t j, uint32_t k) { return (k * (n + 1) + j) * (n + 1) + i; };
    for (uint32_t k = 0; k <= n; ++k)
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t i = 0; i <= n; ++i)
                mesh.positions.push_back({-1.0f + 2.0f * float(i) / float(n), -1.0f + 2.0f * float(j) / float(n), depth * float(k) / float(n)});
    const auto cell = [&](uint8_t type, std::initializer_list<uint32_t> corners) {
        mesh.cellIndex.push_back(uint32_t(mesh.index.size()));
        mesh.cellType.push_back(type);
        mesh.index.insert(mesh.index.end(), corners);
    };
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                // VTK's hexahedron order: the bottom face counter-clockwise seen from above, then the top.
                const uint32_t h[8] = {vertexAt(i, j, k),         vertexAt(i + 1, j, k),         vertexAt(i + 1, j + 1, k),
                                       vertexAt(i, j + 1, k),     vertexAt(i, j, k + 1),         vertexAt(i + 1, j, k + 1),
                                       vertexAt(i + 1, j + 1, k + 1), vertexAt(i, j + 1, k + 1)};
                switch (shape) {
                    case Shape::Hexahedra: cell(12, {h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7]}); break;
                    case Shape::Tetrahedra:  // six around the diagonal 0-6, each with 0, 1, 2 counter-clockwise seen from 3
                        cell(10, {h[0], h[1], h[2], h[6]});
                        cell(10, {h[0], h[2], h[3], h[6]});
                        cell(10, {h[0], h[3], h[7], h[6]});
                        cell(10, {h[0], h[7], h[4], h[6]});
                        cell(10, {h[0], h[4], h[5], h[6]});
                        cell(10, {h[0], h[5], h[1], h[6]});
                        break;
                    case Shape::Wedges:  // two, split along the diagonal 0-2; the first triangle faces away from the second
                        cell(13, {h[0], h[2], h[1], h[4], h[6], h[5]});
                        cell(13, {h[0], h[3], h[2], h[4], h[7], h[6]});
                        break;
                    case Shape::Pyramids: {  // six, one per face, with their apex at the centre
                        const uint32_t centre = uint32_t(mesh.positions.size());
                        glm::vec3 c(0.0f);
                        for (uint32_t v : h) c += mesh.positions[v] / 8.0f;
                        mesh.positions.push_back(c);
                        for (const auto& face : {std::array{0, 1, 2, 3}, std::array{7, 6, 5, 4}, std::array{4, 5, 1, 0},
                                              std::array{5, 6, 2, 1}, std::array{6, 7, 3, 2}, std::array{7, 4, 0, 3}})
                            cell(14, {h[face[0]], h[face[1]], h[face[2]], h[face[3]], centre});
                        break;
                    }
                }
            }
    for (const glm::vec3& p : mesh.positions) mesh.values.push_back(f(p));
    return mesh;
}

core::Volume meshVolume(const core::UnstructuredCells& mesh, float opacity0, float opacity1, float unitDistance, glm::vec3 albedo) {
    core::Volume v;
    v.unstructured = core::prepareUnstructuredGrid(mesh);
    v.valueRange = {0.0f, 1.0f};
    v.colors = {albedo};
    v.opacities = {opacity0, opacity1};
    v.unitDistance = unitDistance;
    return v;
}

// Camera rays straight down through the box against a white background: each pixel shows the box's
// transmittance along the vertical (the medium is black).
test::Mean transmittanceDown(core::Volume volume, float depth, test::Rendered* out = nullptr) {
    core::RenderSettings settings;
    settings.background = glm::vec4(1.0f);
    settings.maxPathLength = 1;
    settings.pixelSamples = 64;
    core::SceneDescription scene;
    scene.volumes.push_back(std::move(volume));
    const test::Rendered image = test::render(scene, test::lookingDown(depth + 1.0f, 1.8f), settings, {24, 24});
    CHECK(image.stats.flaggedRays == 0);
    // Each sample either passes (1) or collides once in the black medium (0).
    double blocked = 0.0;
    for (const glm::vec4& c : image.color) blocked += (1.0 - double(c.r)) * settings.pixelSamples;
    CHECK(image.stats.realCollisions == uint64_t(std::llround(blocked)));
    if (out) *out = image;
    return test::meanRed(image);
}

}  // namespace

TEST_CASE("unstructured volumes: a constant field in each cell shape lets exp(-sigma L) through, sigma 1e-6 to 1e6") {
    test::ValidationGuard guard;
    const float opacity = 1.0f - std::exp(-1.0f);  // over unitDistance 1 / sigma: extinction sigma
    for (const Shape shape : {Shape::Tetrahedra, Shape::Hexahedra, Shape::Wedges, Shape::Pyramids}) {
        for (const float sigma : {1e-6f, 1.0f, 1e6f}) {
            const float depth = 1.0f / sigma;  // optical depth 1; the box's aspect ratio is 2 / depth
            const core::UnstructuredCells mesh = boxMesh(shape, 3, depth, [](glm::vec3) { return 1.0f; });
            const core::Volume volume = meshVolume(mesh, opacity, opacity, 1.0f / sigma, glm::vec3(0.0f));
            CHECK(volume.unstructured->invertedCells == 0);
            CHECK(volume.unstructured->degenerateCells == 0);
            const test::Mean m = transmittanceDown(volume, depth);
            const double expected = std::exp(-1.0);
            CAPTURE(nameOf(shape));
            CAPTURE(sigma);
            MESSAGE(std::string(nameOf(shape)) << ", sigma " << sigma << ": transmittance " << m.mean << " +- " << m.standardError
                                  << ", expected " << expected);
            CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
        }
    }
}

TEST_CASE("unstructured volumes: a linear field is interpolated exactly by every cell shape (the ramp's transmittance)") {
    // Value z / depth, opacity rising linearly with it to o: extinction -ln(1 - o v) sigma, whose mean over the
    // depth is sigma (1 + (1 - o) ln(1 - o) / o) (as in volume_test.cpp). Every shape function reproduces a
    // linear field; an error in a cell's inverse map or weights moves the answer.
    test::ValidationGuard guard;
    const float sigma = 1.0f, depth = 2.0f, opacity = 1.0f - std::exp(-1.0f);
    const double o = opacity, rampMean = 1.0 + (1.0 - o) * std::log(1.0 - o) / o;
    const double expected = std::exp(-double(sigma) * depth * rampMean);
    for (const Shape shape : {Shape::Tetrahedra, Shape::Hexahedra, Shape::Wedges, Shape::Pyramids}) {
        const core::UnstructuredCells mesh = boxMesh(shape, 2, depth, [&](glm::vec3 p) { return p.z / depth; });
        const test::Mean m = transmittanceDown(meshVolume(mesh, 0.0f, opacity, 1.0f / sigma, glm::vec3(0.0f)), depth);
        CAPTURE(nameOf(shape));
        MESSAGE(std::string(nameOf(shape)) << " ramp: transmittance " << m.mean << " +- " << m.standardError << ", expected " << expected);
        CHECK(std::abs(m.mean - expected) <= 0.01 * expected + 4.0 * m.standardError);
    }
}

// The scattering scene both comparisons below render: `volume` lit by a sun, albedo 0.8, several bounces.
test::Rendered litImage(const core::Volume& volume, float depth) {
    core::RenderSettings settings;
    settings.background = glm::vec4(0.2f);
    settings.maxPathLength = 4;
    settings.pixelSamples = 64;
    const test::Rendered image = test::render(test::sunlitVolume(volume), test::lookingDown(depth + 2.0f, 2.2f), settings, {32, 32});
    CHECK(image.stats.flaggedRays == 0);
    return image;
}

// `mesh`'s box mesh values as a structuredRegular grid of (n + 1)^3 nodes over the same box.
core::Volume gridOf(const core::Volume& meshVolume, const core::UnstructuredCells& mesh, uint32_t n, float depth) {
    core::Volume grid = meshVolume;
    grid.unstructured.reset();
    grid.dims = glm::uvec3(n + 1);
    grid.values = std::make_shared<const std::vector<float>>(mesh.values.begin(), mesh.values.begin() + (n + 1) * (n + 1) * (n + 1));
    grid.origin = {-1.0f, -1.0f, 0.0f};
    grid.spacing = glm::vec3(2.0f / float(n), 2.0f / float(n), depth / float(n));
    return grid;
}

// Two images of 32^2 agree block by block (8^2 pixels): means within 1% plus 4 standard errors.
void checkBlocksAgree(const test::Rendered& a, const test::Rendered& b) { CHECK(test::worstBlock(a, b, 8) <= 1.0); }

TEST_CASE("unstructured volumes: the same nodal field on hexahedra and as a structuredRegular grid") {
    // A smooth field on 6^3 nodes: the trilinear interpolant of the hexahedra is the grid's, so the images
    // agree within the noise, block by block.
    test::ValidationGuard guard;
    const uint32_t n = 5;
    const float depth = 2.0f;
    const auto field = [](glm::vec3 p) { return 0.5f + 0.5f * std::sin(2.5f * p.x) * std::cos(2.0f * p.y + p.z); };
    const core::UnstructuredCells mesh = boxMesh(Shape::Hexahedra, n, depth, field);
    const core::Volume hexes = meshVolume(mesh, 0.0f, 0.9f, 0.5f, glm::vec3(0.8f));
    checkBlocksAgree(litImage(hexes, depth), litImage(gridOf(hexes, mesh, n, depth), depth));
}

TEST_CASE("unstructured volumes: a linear field in every cell shape gives the grid's image") {
    // A field linear in x, y and z is reproduced exactly by every shape's interpolant and by the grid's
    // trilinear one: a wrong weight, corner order or inverse map in any shape shows in some block.
    test::ValidationGuard guard;
    const uint32_t n = 3;
    const float depth = 2.0f;
    const auto field = [](glm::vec3 p) { return 0.5f + 0.3f * p.x - 0.15f * p.y + 0.2f * (p.z - 1.0f); };
    std::optional<test::Rendered> gridImage;
    for (const Shape shape : {Shape::Tetrahedra, Shape::Hexahedra, Shape::Wedges, Shape::Pyramids}) {
        const core::UnstructuredCells mesh = boxMesh(shape, n, depth, field);
        const core::Volume volume = meshVolume(mesh, 0.0f, 0.9f, 0.5f, glm::vec3(0.8f));
        if (!gridImage) gridImage = litImage(gridOf(volume, mesh, n, depth), depth);
        CAPTURE(std::string(nameOf(shape)));
        checkBlocksAgree(litImage(volume, depth), *gridImage);
    }
}

namespace {

// The field as the kernels find it at object-space points: (found, value) per point, from the probe kernel.
// Found is 2 where the walk from the start cell's tetrahedron found the point, 1 where only the BVH did.
std::vector<glm::vec2> probe(const core::UnstructuredGrid& grid, const std::vector<glm::vec3>& points) {
    const glm::vec3 scale = glm::vec3(grid.macrocells) * 8.0f / (grid.hi - grid.lo);
    std::vector<glm::vec4> gridPoints;
    for (const glm::vec3& p : points) gridPoints.emplace_back((p - grid.lo) * scale, 0.0f);
    return test::runProbe(shaders::test_unstructured_probe, "test_unstructured_probe", grid.words, gridPoints, uint32_t(0));
}

// The box's inner vertices moved by up to 0.15 of a cell, so that hexahedra and wedges have non-planar faces.
template <class Random>
void jiggle(core::UnstructuredCells& mesh, uint32_t n, Random& random) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float cell = 2.0f / float(n);
    for (glm::vec3& p : mesh.positions) {
        const bool boundary = std::abs(std::abs(p.x) - 1.0f) < 1e-6f || std::abs(std::abs(p.y) - 1.0f) < 1e-6f || p.z < 1e-6f ||
                              p.z > 2.0f - 1e-6f;
        if (!boundary) p += 0.15f * cell * (glm::vec3(unit(random), unit(random), unit(random)) * 2.0f - 1.0f);
    }
}

// `count` random points over boxMesh's [-1, 1]^2, at heights zLow..zHigh (the box spans 0..2).
template <class Random>
std::vector<glm::vec3> randomPoints(Random& random, int count, float zLow = 0.0f, float zHigh = 2.0f) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    for (int i = 0; i < count; ++i) points.push_back({-1.0f + 2.0f * unit(random), -1.0f + 2.0f * unit(random), zLow + (zHigh - zLow) * unit(random)});
    return points;
}

// A linear field: every cell shape's interpolant reproduces it exactly.
float linearField(glm::vec3 p) { return 0.5f + 0.3f * p.x - 0.15f * p.y + 0.2f * p.z; }

}  // namespace

TEST_CASE("unstructured volumes: point location and interpolation are exact, also in cells with curved faces") {
    // The box's inner vertices moved by up to 0.15 of a cell, so that hexahedra and wedges have non-planar
    // faces; a linear field f is still reproduced exactly by every (isoparametric) interpolant, so at any
    // point of the box the kernels must find a cell and return f there, to float precision. Points outside the
    // box find none.
    test::ValidationGuard guard;
    const uint32_t n = 4;
    const auto field = linearField;
    std::mt19937 random(7);
    const std::vector<glm::vec3> inside = randomPoints(random, 2000), outside = randomPoints(random, 200, 2.05f, 3.05f);
    for (const Shape shape : {Shape::Tetrahedra, Shape::Hexahedra, Shape::Wedges, Shape::Pyramids}) {
        core::UnstructuredCells mesh = boxMesh(shape, n, 2.0f, field);
        jiggle(mesh, n, random);
        for (size_t v = 0; v < mesh.positions.size(); ++v) mesh.values[v] = field(mesh.positions[v]);
        const auto grid = core::prepareUnstructuredGrid(mesh);
        CAPTURE(std::string(nameOf(shape)));
        CHECK(grid->degenerateCells == 0);
        CHECK(grid->invertedCells == 0);
        std::vector<glm::vec3> points = inside;
        points.insert(points.end(), outside.begin(), outside.end());
        const std::vector<glm::vec2> results = probe(*grid, points);
        size_t found = 0, exact = 0, foundOutside = 0;
        float worst = 0.0f;
        for (size_t i = 0; i < inside.size(); ++i) {
            if (results[i].x < 1.0f) continue;
            ++found;
            const float error = std::abs(results[i].y - field(inside[i]));
            worst = std::max(worst, error);
            if (error <= 2e-5f) ++exact;
        }
        for (size_t i = inside.size(); i < points.size(); ++i) foundOutside += results[i].x >= 1.0f ? 1 : 0;
        MESSAGE(std::string(nameOf(shape)) << ": " << found << " of " << inside.size() << " found, largest error " << worst);
        CHECK(found == inside.size());
        CHECK(exact == found);
        CHECK(foundOutside == 0);
    }
}

TEST_CASE("unstructured volumes: the walk across tetrahedra's shared faces finds the cell a point is in") {
    // Random points in the jiggled box of tetrahedra, each found by the walk from its start cell's
    // tetrahedron: every point must be found with the exact field, and most by the walk alone; without
    // tetrahedra there is no table to walk. The table itself: 6 n^3 tetrahedra have 12 n^2 faces on the box's
    // boundary and every other face linked both ways.
    test::ValidationGuard guard;
    const uint32_t n = 6;
    const auto field = linearField;
    std::mt19937 random(5);
    const std::vector<glm::vec3> points = randomPoints(random, 2000);
    // The tetrahedra alone, and with one hexahedron above the box (the walk then reads each cell's word).
    for (const auto& [shape, mixed] : {std::pair{Shape::Tetrahedra, false}, std::pair{Shape::Tetrahedra, true}, std::pair{Shape::Hexahedra, false}}) {
        core::UnstructuredCells mesh = boxMesh(shape, n, 2.0f, field);
        jiggle(mesh, n, random);
        if (mixed) {
            const core::UnstructuredCells hexahedron = boxMesh(Shape::Hexahedra, 1, 0.5f, field);
            mesh.cellIndex.push_back(uint32_t(mesh.index.size()));
            mesh.cellType.push_back(12);
            for (uint32_t i : hexahedron.index) mesh.index.push_back(uint32_t(mesh.positions.size()) + i);
            for (const glm::vec3& p : hexahedron.positions) mesh.positions.push_back(p + glm::vec3(0.0f, 0.0f, 2.5f));
        }
        mesh.values.clear();
        for (const glm::vec3& p : mesh.positions) mesh.values.push_back(field(p));
        const auto grid = core::prepareUnstructuredGrid(mesh);
        gpu::UnstructuredHeader header;
        std::memcpy(&header, grid->words.data(), sizeof header);
        CAPTURE(std::string(nameOf(shape)));
        CAPTURE(mixed);
        if (shape == Shape::Tetrahedra) {
            REQUIRE(header.neighbours ==
                    (mixed ? gpu::UNSTRUCTURED_NEIGHBOURS_SOME_TETRAHEDRA : gpu::UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA));
            // A tetrahedron's neighbours follow its 4 indices.
            const auto neighbour = [&](uint32_t c, uint32_t k) {
                return grid->words[header.indexOffset + (grid->words[header.cellOffset + c] >> 2) + 4 + k];
            };
            size_t boundary = 0, mutual = 0;
            for (uint32_t c = 0; c < header.cellCount; ++c)
                for (uint32_t k = 0; k < 4 && (grid->words[header.cellOffset + c] & 3u) == gpu::UNSTRUCTURED_TETRAHEDRON; ++k) {
                    const uint32_t other = neighbour(c, k);
                    if (other == gpu::UNSTRUCTURED_NO_CELL) {
                        ++boundary;
                        continue;
                    }
                    for (uint32_t j = 0; j < 4; ++j) mutual += neighbour(other, j) == c ? 1 : 0;
                }
            CHECK(boundary == 12 * n * n);
            CHECK(mutual + boundary == 4 * (header.cellCount - (mixed ? 1 : 0)));
        } else {
            CHECK(header.neighbours == gpu::UNSTRUCTURED_NEIGHBOURS_NONE);
        }
        const std::vector<glm::vec2> results = probe(*grid, points);
        size_t found = 0, walked = 0, exact = 0;
        for (size_t i = 0; i < points.size(); ++i) {
            found += results[i].x >= 1.0f ? 1 : 0;
            walked += results[i].x == 2.0f ? 1 : 0;
            exact += results[i].x >= 1.0f && std::abs(results[i].y - field(points[i])) <= 2e-5f ? 1 : 0;
        }
        MESSAGE(std::string(nameOf(shape)) << std::string(mixed ? " and a hexahedron" : "") << ": " << found << " of " << points.size()
                                           << " found, " << walked << " by the walk, " << exact << " exact");
        CHECK(found == points.size());
        CHECK(exact == points.size());
        if (shape == Shape::Tetrahedra) CHECK(walked >= points.size() * 95 / 100);
        else CHECK(walked == 0);
    }
}

TEST_CASE("unstructured volumes: the walk through inverted tetrahedra with cell values finds the containing cell's value") {
    // The jiggled box of tetrahedra with every other cell's corners 1 and 2 swapped (inverted, which is kept)
    // and a value per cell, different in every cell: each of 2000 random points must be found, mostly by the
    // walk, with the value of a cell that holds it (found on the host by barycentric coordinates in double,
    // with the kernels' tolerance; a point on a shared face may take either cell's).
    test::ValidationGuard guard;
    const uint32_t n = 5;
    std::mt19937 random(9);
    core::UnstructuredCells mesh = boxMesh(Shape::Tetrahedra, n, 2.0f, [](glm::vec3) { return 0.0f; });
    jiggle(mesh, n, random);
    mesh.cellCentered = true;
    mesh.values.clear();
    for (size_t c = 0; c < mesh.cellType.size(); ++c) {
        if (c % 2 == 1) std::swap(mesh.index[mesh.cellIndex[c] + 1], mesh.index[mesh.cellIndex[c] + 2]);
        mesh.values.push_back(float(c) / float(mesh.cellType.size()));
    }
    const auto grid = core::prepareUnstructuredGrid(mesh);
    CHECK(grid->invertedCells == mesh.cellType.size() / 2);
    const std::vector<glm::vec3> points = randomPoints(random, 2000);
    const std::vector<glm::vec2> results = probe(*grid, points);
    size_t found = 0, walked = 0, right = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        found += results[i].x >= 1.0f ? 1 : 0;
        walked += results[i].x == 2.0f ? 1 : 0;
        bool matches = false;
        for (size_t c = 0; c < mesh.cellType.size() && !matches; ++c) {
            glm::dvec3 x[4];
            for (int k = 0; k < 4; ++k) x[k] = glm::dvec3(mesh.positions[mesh.index[mesh.cellIndex[c] + k]]);
            const glm::dvec3 b = glm::inverse(glm::dmat3(x[1] - x[0], x[2] - x[0], x[3] - x[0])) * (glm::dvec3(points[i]) - x[0]);
            const bool holds = b.x >= -1e-4 && b.y >= -1e-4 && b.z >= -1e-4 && b.x + b.y + b.z <= 1.0 + 1e-4;
            matches = holds && results[i].y == mesh.values[c];
        }
        right += results[i].x >= 1.0f && matches ? 1 : 0;
    }
    MESSAGE(found << " of " << points.size() << " found, " << walked << " by the walk, " << right << " with a holding cell's value");
    CHECK(found == points.size());
    CHECK(right == points.size());
    CHECK(walked >= points.size() * 95 / 100);
}

TEST_CASE("unstructured volumes: small hexahedra far from the grid's origin are still found") {
    // 1000 hexahedra of side 10 (the median cell, so the macrocells' size) and 1000 of side 0.25 placed 200
    // away: in grid space the small cells are 0.2 units wide at coordinates about 160, where a Newton
    // residual summed from absolute coordinates carries rounding of the small cells' own tolerance.
    test::ValidationGuard guard;
    const auto field = [](glm::vec3 p) { return 0.01f * p.x - 0.02f * p.y + 0.03f * p.z; };
    core::UnstructuredCells mesh;
    for (const auto& [origin, side] : {std::pair{glm::vec3(0.0f), 10.0f}, std::pair{glm::vec3(200.0f), 0.25f}}) {
        const core::UnstructuredCells box = boxMesh(Shape::Hexahedra, 10, 2.0f, field);
        const uint32_t first = uint32_t(mesh.positions.size()), firstIndex = uint32_t(mesh.index.size());
        for (const glm::vec3& p : box.positions) {
            // boxMesh spans [-1, 1]^2 x [0, 2]: moved to origin + [0, 10 side]^3.
            mesh.positions.push_back(origin + (p + glm::vec3(1.0f, 1.0f, 0.0f)) * 5.0f * side);
            mesh.values.push_back(field(mesh.positions.back()));
        }
        for (uint32_t i : box.index) mesh.index.push_back(first + i);
        for (uint32_t c : box.cellIndex) mesh.cellIndex.push_back(firstIndex + c);
        mesh.cellType.insert(mesh.cellType.end(), box.cellType.begin(), box.cellType.end());
    }
    const auto grid = core::prepareUnstructuredGrid(mesh);
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back(glm::vec3(200.0f) + 2.5f * glm::vec3(unit(random), unit(random), unit(random)));
    const std::vector<glm::vec2> results = probe(*grid, points);
    size_t found = 0, exact = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        found += results[i].x >= 1.0f ? 1 : 0;
        exact += results[i].x >= 1.0f && std::abs(results[i].y - field(points[i])) <= 1e-4f ? 1 : 0;
    }
    MESSAGE(found << " of " << points.size() << " points in the small cells found, " << exact << " exact");
    CHECK(found == points.size());
    CHECK(exact == points.size());
}

TEST_CASE("unstructured volumes: degenerate cells are dropped and inverted ones kept, both reported; no NaN") {
    test::ValidationGuard guard;
    const float depth = 1.0f, opacity = 1.0f - std::exp(-1.0f);
    core::UnstructuredCells mesh = boxMesh(Shape::Tetrahedra, 2, depth, [](glm::vec3) { return 1.0f; });
    std::swap(mesh.index[mesh.cellIndex[5] + 1], mesh.index[mesh.cellIndex[5] + 2]);  // cell 5 inverted
    // Two cells of no volume: a repeated corner, and four corners in a plane; and a needle 10^6 times longer
    // than wide, inside the box, whose value is that of the box.
    const uint32_t first = uint32_t(mesh.positions.size());
    for (const glm::vec3 p : {glm::vec3(0.1f, 0.1f, 0.5f), glm::vec3(0.3f, 0.1f, 0.5f), glm::vec3(0.1f, 0.3f, 0.5f),
                              glm::vec3(0.3f, 0.3f, 0.5f), glm::vec3(0.0f, 0.0f, 0.1f), glm::vec3(1e-6f, 0.0f, 0.1f),
                              glm::vec3(0.0f, 1e-6f, 0.1f), glm::vec3(0.0f, 0.0f, 0.9f)}) {
        mesh.positions.push_back(p);
        mesh.values.push_back(1.0f);
    }
    for (const std::array<uint32_t, 4> cell : {std::array{0u, 1u, 1u, 2u}, std::array{0u, 1u, 2u, 3u}, std::array{4u, 5u, 6u, 7u}}) {
        mesh.cellIndex.push_back(uint32_t(mesh.index.size()));
        mesh.cellType.push_back(10);
        for (uint32_t v : cell) mesh.index.push_back(first + v);
    }
    const core::Volume volume = meshVolume(mesh, opacity, opacity, 1.0f, glm::vec3(0.0f));
    CHECK(volume.unstructured->degenerateCells == 2);
    CHECK(volume.unstructured->invertedCells == 1);
    REQUIRE(volume.unstructured->warnings.size() == 2);
    CHECK(volume.unstructured->warnings[0].find("cell 48") != std::string::npos);  // the first degenerate one
    CHECK(volume.unstructured->warnings[1].find("cell 5") != std::string::npos);
    // The needle overlaps the box's cells: where both hold a point the field is still 1, so the
    // transmittance is still exp(-1), and the inverted cell still counts.
    const test::Mean m = transmittanceDown(volume, depth);
    MESSAGE("with degenerate, inverted and needle cells: " << m.mean << " +- " << m.standardError);
    CHECK(std::isfinite(m.mean));
    CHECK(std::abs(m.mean - std::exp(-1.0)) <= 0.01 * std::exp(-1.0) + 4.0 * m.standardError);
}

TEST_CASE("unstructured volumes: meshes that cannot be rendered are refused, naming the problem") {
    const core::UnstructuredCells good = boxMesh(Shape::Hexahedra, 1, 1.0f, [](glm::vec3) { return 0.5f; });
    const auto refusal = [](const core::UnstructuredCells& mesh) {
        return test::refusalOf([&] { core::prepareUnstructuredGrid(mesh); });
    };
    CHECK(refusal(good).empty());
    core::UnstructuredCells bad = good;
    bad.index[3] = 8;
    CHECK(refusal(bad) == "index 3 is 8, past the 8 vertices");
    bad = good;
    bad.cellType[0] = 42;
    CHECK(refusal(bad).find("cell 0 has type 42") == 0);
    bad = good;
    bad.cellIndex[0] = 1;
    CHECK(refusal(bad) == "cell 0's 8 indices from 1 run past the 8 of the index array");
    bad = good;
    bad.values[2] = NAN;
    CHECK(refusal(bad) == "vertex 2's value is not finite");
    bad = good;
    bad.positions[7].y = INFINITY;
    CHECK(refusal(bad) == "vertex 7's position is not finite");
    bad = good;
    bad.cellCentered = true;
    CHECK(refusal(bad) == "8 values for 1 cells");
    bad = good;
    for (glm::vec3& p : bad.positions) p.z = 0.0f;
    CHECK(refusal(bad) == "no cell has volume (all 1 are degenerate)");
    bad = good;
    for (glm::vec3& p : bad.positions) p *= 3e38f;  // finite, but the box is 6e38 wide
    CHECK(refusal(bad) == "the mesh's box is wider than a float can hold");
}

namespace {

// The iso-surface of `mesh` at `isovalue` seen straight down from z = 3 (orthographic, 24^2, one sample):
// depth, world normal and primitive id per pixel.
struct IsoView {
    std::vector<float> depth;
    std::vector<glm::vec3> normal;
    std::vector<uint32_t> primitiveId;
};

IsoView viewIsosurface(const core::UnstructuredCells& mesh, std::vector<float> isovalues, float height = 1.8f) {
    core::SceneDescription scene;
    core::IsosurfaceSet set;
    set.mesh = core::prepareUnstructuredGrid(mesh);
    set.isovalues = std::move(isovalues);
    scene.isosurfaceSets.push_back(set);
    scene.materials.push_back(core::Material{});
    scene.instances.push_back({{core::GeometryKind::Isosurfaces, 0}, glm::mat4(1.0f), 0});
    core::Scene built(test::testContext(), scene);
    core::PathTracer tracer(test::testContext());
    core::FrameChannels channels;
    channels.depth = channels.normal = channels.primitiveId = true;
    const glm::uvec2 size(24, 24);
    tracer.resize(size, channels);
    core::RenderSettings settings;
    settings.pixelSamples = 1;
    (void)tracer.render(built, test::lookingDown(3.0f, height), settings);
    IsoView view;
    view.depth.resize(size_t(size.x) * size.y);
    view.normal.resize(view.depth.size());
    view.primitiveId.resize(view.depth.size());
    tracer.readDepth(view.depth.data());
    tracer.readChannel(core::SurfaceChannel::Normal, view.normal.data());
    tracer.readChannel(core::SurfaceChannel::PrimitiveId, view.primitiveId.data());
    return view;
}

}  // namespace

TEST_CASE("unstructured iso-surfaces: a linear field's surfaces are exact planes in every cell shape") {
    // Every shape's interpolant reproduces a linear field, so its iso-surface is a plane, found by root
    // finding in each cell's own interpolant (inner vertices moved, so hexahedra and wedges have curved
    // faces). f = z: the depth from z = 3 through the surface at 0.7 is 2.3 at every pixel. f = a . p: the
    // normal is along a at every pixel. The primitive id is the isovalue's index.
    test::ValidationGuard guard;
    const glm::vec3 a = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    for (const Shape shape : {Shape::Tetrahedra, Shape::Hexahedra, Shape::Wedges, Shape::Pyramids}) {
        CAPTURE(std::string(nameOf(shape)));
        for (const bool tilted : {false, true}) {
            const auto field = [&](glm::vec3 p) { return tilted ? glm::dot(a, p) : p.z; };
            // 2.5 deep: the grid's scale differs between the axes (macrocells 2 x 2 x 3 over 2 x 2 x 2.5).
            core::UnstructuredCells mesh = boxMesh(shape, 3, 2.5f, field);
            std::mt19937 random(3);
            std::uniform_real_distribution<float> jitter(-0.07f, 0.07f);
            for (glm::vec3& p : mesh.positions)
                if (std::abs(std::abs(p.x) - 1.0f) > 1e-6f && std::abs(std::abs(p.y) - 1.0f) > 1e-6f && p.z > 1e-6f && p.z < 2.5f - 1e-6f)
                    p += glm::vec3(jitter(random), jitter(random), jitter(random));
            for (size_t v = 0; v < mesh.positions.size(); ++v) mesh.values[v] = field(mesh.positions[v]);
            // At 0.8 the tilted plane stays inside the box under the whole view; -5 crosses no cell.
            const IsoView view = viewIsosurface(mesh, {-5.0f, tilted ? 0.8f : 0.7f});
            float worstDepth = 0.0f, worstNormal = 0.0f;
            size_t hits = 0, idOne = 0;
            for (size_t i = 0; i < view.depth.size(); ++i) {
                if (!std::isfinite(view.depth[i])) continue;
                ++hits;
                idOne += view.primitiveId[i] == 1 ? 1 : 0;
                if (!tilted) worstDepth = std::max(worstDepth, std::abs(view.depth[i] - 2.3f));
                else worstNormal = std::max(worstNormal, 1.0f - std::abs(glm::dot(glm::normalize(view.normal[i]), a)));
            }
            MESSAGE((std::string(nameOf(shape)) + (tilted ? " tilted: " : " level: ")) << hits << " of " << view.depth.size()
                                  << " pixels hit; largest depth error " << worstDepth << ", largest 1 - |cos(normal, a)| " << worstNormal);
            CHECK(hits == view.depth.size());
            CHECK(idOne == hits);
            CHECK(worstDepth <= 1e-5f);
            CHECK(worstNormal <= 1e-5f);
        }
    }
}

TEST_CASE("unstructured iso-surfaces: a surface the ray crosses twice within one sampling step is found") {
    // One hexahedron, a box of 1 x s x 1 (s = 17/15) with f = x y / s at its corners (x, y its edges' lengths
    // from corner 0): the trilinear interpolant is that product itself. It stands rotated so that the camera's
    // rays run along (1, -1, 0) in its coordinates: each ray keeps x + y = c, along it f = x (c - x) / s peaks
    // at c^2 / (4 s), at the middle of the ray's depth through the box. The surface f = 0.2 is crossed twice when
    // c > c0 = 2 sqrt(0.2 s), and the view is 0.01 wide across that silhouette (c = c0 + sqrt(2) X at image
    // X). The 16 sampling steps over the box are 0.1 deep, and s puts the peak halfway between two samples:
    // in 0 < X < 0.0016 (about four pixel columns) both crossings lie between the same two samples, where
    // sampling alone sees the interpolant below the isovalue at every sample; the turning point of the step's
    // cubic splits the step there. Pixels more than a column right of the silhouette must all be hit, those
    // more than a column left of it none. Sampling alone (the code before) fails it.
    test::ValidationGuard guard;
    const float iso = 0.2f, s = 17.0f / 15.0f;
    // Box coordinates to world: e1 -> (1, 0, -1) / sqrt 2, e2 -> (1, 0, 1) / sqrt 2, e3 -> (0, -1, 0) (a
    // rotation), then the silhouette moved to X = 0 and the box's middle to Y = 0.
    const float r = 1.0f / std::sqrt(2.0f);
    const glm::mat3 rotation(glm::vec3(r, 0.0f, -r), glm::vec3(r, 0.0f, r), glm::vec3(0.0f, -1.0f, 0.0f));
    const glm::vec3 shift(-r * 2.0f * std::sqrt(iso * s), 0.5f, 0.0f);
    core::UnstructuredCells mesh;
    for (const glm::vec3& corner : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0),
                                    glm::vec3(0, 0, 1), glm::vec3(1, 0, 1), glm::vec3(1, 1, 1), glm::vec3(0, 1, 1)}) {
        mesh.positions.push_back(rotation * (corner * glm::vec3(1.0f, s, 1.0f)) + shift);
        mesh.values.push_back(corner.x * corner.y);  // x y / s at the corner (x, s y)
    }
    mesh.index = {0, 1, 2, 3, 4, 5, 6, 7};
    mesh.cellIndex = {0};
    mesh.cellType = {12};
    CHECK(core::prepareUnstructuredGrid(mesh)->invertedCells == 0);
    const float width = 0.01f;
    const std::vector<float> depth = viewIsosurface(mesh, {iso}, width).depth;
    const uint32_t n = 24;  // viewIsosurface's image
    size_t rightHit = 0, right = 0, leftHit = 0, left = 0;
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            const float X = test::groundPoint(width, n, float(x) + 0.5f, float(y) + 0.5f).x, pixel = width / float(n);
            const bool hit = std::isfinite(depth[size_t(y) * n + x]);
            if (X > pixel) {
                ++right;
                rightHit += hit ? 1 : 0;
            } else if (X < -pixel) {
                ++left;
                leftHit += hit ? 1 : 0;
            }
        }
    MESSAGE(rightHit << " of " << right << " pixels right of the silhouette hit, " << leftHit << " of " << left << " left of it");
    CHECK(right > 0);
    CHECK(rightHit == right);
    CHECK(leftHit == 0);
}

TEST_CASE("unstructured volumes: random hostile meshes are refused by name or render without NaN") {
    // 400 meshes of random cells over few vertices: random types (some unknown), indices (some past the
    // vertices), index spans (some past the array), values and positions (some NaN, Inf or 1e38). Each is
    // refused with std::invalid_argument or prepared; every 10th prepared one is rendered, and its image is
    // finite. Under the sanitizer build this also checks that preparing reads and writes nothing out of bounds.
    test::ValidationGuard guard;
    std::mt19937 random(2026);
    const auto pick = [&](uint32_t n) { return uint32_t(random() % n); };
    const float specials[] = {NAN, INFINITY, -INFINITY, 1e38f, -1e38f, 0.0f};
    size_t refused = 0, prepared = 0, rendered = 0;
    for (int m = 0; m < 400; ++m) {
        core::UnstructuredCells mesh;
        const uint32_t vertices = 1 + pick(12);
        for (uint32_t v = 0; v < vertices; ++v) {
            glm::vec3 p(float(pick(5)), float(pick(5)), float(pick(5)));
            if (pick(50) == 0) p[int(pick(3))] = specials[pick(6)];
            mesh.positions.push_back(p);
        }
        const uint32_t cells = 1 + pick(6);
        mesh.cellCentered = pick(2) == 0;
        for (uint32_t c = 0; c < cells; ++c) {
            const uint8_t types[] = {10, 12, 13, 14, 42};
            mesh.cellType.push_back(pick(30) == 0 ? types[4] : types[pick(4)]);
            mesh.cellIndex.push_back(uint32_t(mesh.index.size()) + (pick(30) == 0 ? pick(20) : 0));
            const uint32_t corners = pick(20) == 0 ? pick(9) : std::max(core::unstructuredCorners(mesh.cellType.back()), 1u);
            for (uint32_t k = 0; k < corners; ++k) mesh.index.push_back(pick(40) == 0 ? vertices + pick(3) : pick(vertices));
        }
        const size_t valueCount = mesh.cellCentered ? cells : vertices;
        for (size_t i = 0; i < valueCount + (pick(30) == 0 ? 1 : 0); ++i)
            mesh.values.push_back(pick(40) == 0 ? specials[pick(6)] : float(pick(100)) / 100.0f);
        std::shared_ptr<const core::UnstructuredGrid> grid;
        try {
            grid = core::prepareUnstructuredGrid(mesh);
        } catch (const std::invalid_argument& e) {
            CHECK(std::string(e.what()).size() > 0);
            ++refused;
            continue;
        }
        ++prepared;
        REQUIRE(grid->cellsKept > 0);
        if (prepared % 10 != 1) continue;
        core::Volume volume;
        volume.unstructured = grid;
        volume.valueRange = {0.0f, 1.0f};
        volume.opacities = {0.2f, 0.9f};
        volume.colors = {glm::vec3(0.8f)};
        core::SceneDescription scene;
        scene.volumes.push_back(volume);
        core::Light sun;
        sun.kind = core::Light::Kind::Directional;
        sun.direction = glm::normalize(glm::vec3(0.2f, -0.3f, -1.0f));
        sun.intensity = 2.0f;
        scene.lights.push_back(sun);
        core::RenderSettings settings;
        settings.pixelSamples = 4;
        settings.maxPathLength = 3;
        core::Camera camera = test::lookingDown(8.0f, 10.0f);
        camera.position = glm::vec3(2.0f, 2.0f, 8.0f);
        const test::Rendered image = test::render(scene, camera, settings, {16, 16});
        for (const glm::vec4& c : image.color) CHECK(std::isfinite(c.r + c.g + c.b + c.a));
        CHECK(image.stats.flaggedRays == 0);
        ++rendered;
    }
    MESSAGE(refused << " refused, " << prepared << " prepared, " << rendered << " rendered");
    CHECK(refused > 40);
    CHECK(prepared > 40);
}
