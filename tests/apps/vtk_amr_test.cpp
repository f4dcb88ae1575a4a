// VTK AMR sets (io/vtk/VtkAmrFile): the shared hierarchical box data set reads as its XML declares (81
// blocks on 4 levels, each block's amr_box), and its own cell arrays confirm the reading: every cell of a
// block holds the block's id in 'BlockId' and its level in 'Depth'. A multiblock set written here (two
// spacings) reads back level, placement and value for value. ripple-render draws the shared set. Hostile
// sets (escaping or absolute block paths, boxes that disagree with their blocks, spacings of no common
// ratio, blocks off their level's grid) are refused by name. Split over 2 to 4 ranks (AmrPartition), every cell
// lies on exactly one rank, and at random points the rank whose blocks hold the point finds the whole's finest
// cell there.
#include "apps/scene/AmrPartition.h"
#include "io/vtk/VtkAmrFile.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <regex>
#include <string>

using namespace ripple;
using namespace ripple::test;

namespace {

// A .vti with one cell array `name` (ascii) over cells x cells y cells z from `origin` at `spacing`.
std::string imageText(glm::uvec3 cells, glm::vec3 origin, float spacing, const std::vector<float>& values) {
    std::string v;
    for (float x : values) v += std::to_string(x) + " ";
    const std::string extent = "0 " + std::to_string(cells.x) + " 0 " + std::to_string(cells.y) + " 0 " + std::to_string(cells.z);
    return "<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<ImageData WholeExtent=\"" + extent +
           "\" Origin=\"" + std::to_string(origin.x) + " " + std::to_string(origin.y) + " " + std::to_string(origin.z) +
           "\" Spacing=\"" + std::to_string(spacing) + " " + std::to_string(spacing) + " " + std::to_string(spacing) +
           "\">\n<Piece Extent=\"" + extent + "\"><CellData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">" + v +
           "</DataArray></CellData></Piece></ImageData></VTKFile>\n";
}

std::string multiblock(const std::vector<std::string>& files) {
    std::string text = "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\"><vtkMultiBlockDataSet><Block index=\"0\">";
    for (size_t i = 0; i < files.size(); ++i) text += "<DataSet index=\"" + std::to_string(i) + "\" file=\"" + files[i] + "\"/>";
    return text + "</Block></vtkMultiBlockDataSet></VTKFile>\n";
}

// The finest cell of `amr` holding object-space point p: (level, value); level -1 where no block does.
std::pair<int, float> finestCell(const apps::AmrData& amr, glm::dvec3 p) {
    std::pair<int, float> best{-1, 0.0f};
    for (const apps::AmrData::Block& b : amr.blocks) {
        const glm::dvec3 cellSize = glm::dvec3(amr.spacing) * double(amr.cellWidth[b.level]);
        const glm::ivec3 c(glm::floor((p - glm::dvec3(amr.origin)) / cellSize));
        if (glm::any(glm::lessThan(c, b.lower)) || glm::any(glm::greaterThan(c, b.upper)) || int(b.level) <= best.first) continue;
        const glm::ivec3 d = b.upper - b.lower + 1, i = c - b.lower;
        best = {int(b.level), b.values[size_t((i.z * d.y + i.y) * d.x + i.x)]};
    }
    return best;
}

void checkPartition(const apps::AmrData& whole) {
    const auto [lo, hi] = apps::amrBounds(whole);
    std::mt19937 random(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back(lo + (hi - lo) * glm::dvec3(unit(random), unit(random), unit(random)));
    for (uint32_t ranks = 2; ranks <= 4; ++ranks) {
        CAPTURE(ranks);
        std::vector<apps::AmrData> parts;
        uint64_t cells = 0;
        for (uint32_t r = 0; r < ranks; ++r) {
            parts.push_back(apps::amrPart(whole, r, ranks));
            cells += parts.back().cells;
        }
        CHECK(cells == whole.cells);
        uint32_t wrong = 0;
        for (const glm::dvec3& p : points) {
            const std::pair<int, float> expected = finestCell(whole, p);
            uint32_t holders = 0;
            for (const apps::AmrData& part : parts) {
                const std::pair<int, float> found = finestCell(part, p);
                if (found.first < 0) continue;
                ++holders;
                wrong += found != expected;
            }
            wrong += holders != (expected.first < 0 ? 0u : 1u);
        }
        CHECK(wrong == 0);
    }
}

}  // namespace

TEST_CASE("VTK AMR: the shared hierarchical box data set reads as it declares; its own arrays confirm it") {
    const std::filesystem::path file = std::filesystem::path(RIPPLE_DATA_DIR) / "vtk" / "amr" / "HierarchicalBoxDataset.v1.1.vthb";
    if (!std::filesystem::exists(file)) {
        MESSAGE("skipped: " << file.string() << " is absent");
        return;
    }
    const apps::AmrData ids = apps::readVtkAmr(file, {"BlockId", -1});
    const apps::AmrData depth = apps::readVtkAmr(file, {"Depth", -1});
    REQUIRE(ids.blocks.size() == 81);
    REQUIRE(depth.blocks.size() == 81);
    CHECK(ids.cellWidth == std::vector<float>{1.0f, 0.5f, 0.25f, 0.125f});
    CHECK(ids.origin == glm::vec3(-1.75f, -1.25f, 0.0f));
    // The set's own text: the amr_box and file of every DataSet, in order.
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::regex dataSet("amr_box=\"(-?\\d+) (-?\\d+) (-?\\d+) (-?\\d+) (-?\\d+) (-?\\d+)\" file=\"[^\"]*_(\\d+)\\.vti\"");
    size_t i = 0;
    uint64_t declaredCells = 0;
    for (auto m = std::sregex_iterator(text.begin(), text.end(), dataSet); m != std::sregex_iterator(); ++m, ++i) {
        REQUIRE(i < ids.blocks.size());
        const apps::AmrData::Block& b = ids.blocks[i];
        const glm::ivec3 lower(std::stoi((*m)[1]), std::stoi((*m)[3]), std::stoi((*m)[5]));
        const glm::ivec3 upper(std::stoi((*m)[2]), std::stoi((*m)[4]), std::stoi((*m)[6]));
        CAPTURE(i);
        CHECK(b.lower == lower);
        CHECK(b.upper == upper);
        const glm::ivec3 n = upper - lower + 1;
        declaredCells += uint64_t(n.x) * n.y * n.z;
        // Every cell of block file _k holds k in 'BlockId' and the block's level in 'Depth'.
        const float id = float(std::stoi((*m)[7]));
        CHECK(std::all_of(b.values.begin(), b.values.end(), [&](float v) { return v == id; }));
        CHECK(std::all_of(depth.blocks[i].values.begin(), depth.blocks[i].values.end(),
                          [&](float v) { return v == float(depth.blocks[i].level); }));
    }
    CHECK(i == 81);
    CHECK(ids.cells == declaredCells);
    // Levels 0 to 3, as the <Block level> elements say.
    CHECK(ids.blocks.front().level == 0);
    CHECK(ids.blocks.back().level == 3);

    TempFolder dir;
    checkPartition(ids);

    const ProgramRun run = runRender("--volume '" + file.string() + "' --field 'Fractal Volume Fraction' --size 32x32 --spp 2 -o '" +
                                     (dir / "amr.pfm").string() + "'");
    CHECK_MESSAGE(run.exitCode == 0, run.output);
    CHECK(!contains(run.output, "ERROR"));
    CHECK(contains(run.output, "real and"));  // its volume statistics: the hierarchy was tracked
}

TEST_CASE("VTK AMR: a multiblock set of image data at two spacings reads back") {
    TempFolder dir;
    std::filesystem::create_directories(dir / "blocks");
    // Level 0: 4x2x2 cells of 1 from (10, 0, 0); level 1: 2x2x2 cells of 0.5 from (11, 0.5, 0).
    std::vector<float> coarse(16), fine(8);
    for (size_t k = 0; k < coarse.size(); ++k) coarse[k] = float(k);
    for (size_t k = 0; k < fine.size(); ++k) fine[k] = 100.0f + float(k);
    writeText(dir / "blocks" / "a.vti", imageText({4, 2, 2}, {10.0f, 0.0f, 0.0f}, 1.0f, coarse));
    writeText(dir / "blocks" / "b.vti", imageText({2, 2, 2}, {11.0f, 0.5f, 0.0f}, 0.5f, fine));
    const apps::AmrData amr = apps::readVtkAmr(writeText(dir / "set.vtm", multiblock({"blocks/b.vti", "blocks/a.vti"})));
    REQUIRE(amr.blocks.size() == 2);
    CHECK(amr.cellWidth == std::vector<float>{1.0f, 0.5f});
    CHECK(amr.origin == glm::vec3(10.0f, 0.0f, 0.0f));
    CHECK(amr.blocks[0].level == 1);
    CHECK(amr.blocks[0].lower == glm::ivec3(2, 1, 0));
    CHECK(amr.blocks[0].upper == glm::ivec3(3, 2, 1));
    CHECK(amr.blocks[0].values == fine);
    CHECK(amr.blocks[1].level == 0);
    CHECK(amr.blocks[1].lower == glm::ivec3(0));
    CHECK(amr.blocks[1].upper == glm::ivec3(3, 1, 1));
    CHECK(amr.blocks[1].values == coarse);
    CHECK(amr.minValue == 0.0f);
    CHECK(amr.maxValue == 107.0f);
    checkPartition(amr);
}

TEST_CASE("VTK AMR: hostile sets are refused by name") {
    TempFolder dir;
    std::filesystem::create_directories(dir / "inner");
    writeText(dir / "outside.vti", imageText({1, 1, 1}, glm::vec3(0.0f), 1.0f, {1.0f}));
    writeText(dir / "inner" / "a.vti", imageText({2, 2, 2}, glm::vec3(0.0f), 1.0f, std::vector<float>(8, 1.0f)));
    writeText(dir / "inner" / "off.vti", imageText({2, 2, 2}, glm::vec3(0.25f), 0.5f, std::vector<float>(8, 1.0f)));
    writeText(dir / "inner" / "skew.vti",
              "<VTKFile type=\"ImageData\" version=\"0.1\"><ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"0.5 0.25 0.5\">"
              "<Piece Extent=\"0 1 0 1 0 1\"><CellData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">1</DataArray>"
              "</CellData></Piece></ImageData></VTKFile>\n");
    const std::string hierarchical = "<VTKFile type=\"vtkOverlappingAMR\" version=\"1.1\"><vtkOverlappingAMR origin=\"0 0 0\">"
                                     "<Block level=\"0\" spacing=\"1 1 1\"><DataSet index=\"0\" amr_box=\"0 1 0 1 0 2\" "
                                     "file=\"a.vti\"/></Block></vtkOverlappingAMR></VTKFile>\n";
    struct Case {
        const char* name;
        std::string text;
        const char* problem;
    };
    for (const Case& c : {Case{"escape.vtm", multiblock({"../outside.vti"}), "resolves outside the header's folder"},
                          Case{"absolute.vtm", multiblock({(dir / "outside.vti").string()}), "is an absolute path"},
                          Case{"missing.vtm", multiblock({"none.vti"}), "none.vti"},
                          Case{"box.vthb", hierarchical, "cells disagree with the set's amr_box 2x2x3"},
                          Case{"off.vtm", multiblock({"a.vti", "off.vti"}), "its origin is not on level 1's grid"},
                          Case{"skew.vtm", multiblock({"a.vti", "skew.vti"}), "divided by one ratio on every axis"},
                          Case{"empty.vtm", multiblock({}), "lists no block file"},
                          Case{"polydata.vtm", "<VTKFile type=\"PolyData\"/>", "an AMR set is vtkOverlappingAMR"},
                          Case{"notxml.vthb", "<<<", "is not XML"}}) {
        CAPTURE(c.name);
        const std::filesystem::path file = writeText(dir / "inner" / c.name, c.text);
        CHECK_THROWS_WITH_AS(apps::readVtkAmr(file), doctest::Contains(c.problem), apps::VolumeError);
    }
}
