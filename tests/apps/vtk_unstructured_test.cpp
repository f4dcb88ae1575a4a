// The VTK unstructured-grid reader (io/vtk/VtkUnstructuredFile): grids written here (legacy ASCII with the
// old cell lists, legacy 5.1 BINARY with OFFSETS and CONNECTIVITY, XML ascii and zlib-appended) read back
// cell for cell; hostile grids refused naming the cell; the shared files against an independent reader
// (Debian's meshio, run at test time) and, where meshio cannot read one, against what the file declares.
#include "io/vtk/VtkUnstructuredFile.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

using namespace ripple::apps;
using namespace ripple::test;

namespace {

// Four cells of the four kinds, then a voxel and a quadratic tetrahedron, over 14 points on a line (the
// reader checks topology, not shape); a point field p and a cell field c.
const std::vector<int> kTypes = {10, 12, 13, 14, 11, 24};
const std::vector<std::vector<int>> kCells = {{0, 1, 2, 3},
                                              {0, 1, 2, 3, 4, 5, 6, 7},
                                              {1, 2, 3, 4, 5, 6},
                                              {2, 3, 4, 5, 6},
                                              {0, 1, 2, 3, 4, 5, 6, 7},
                                              {4, 5, 6, 7, 8, 9, 10, 11, 12, 13}};
constexpr int kPoints = 14;

std::string legacyAscii() {
    std::ostringstream f;
    f << "# vtk DataFile Version 3.0\ncells\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " << kPoints << " float\n";
    for (int p = 0; p < kPoints; ++p) f << p << " " << 2 * p << " " << 3 * p << "\n";
    size_t size = 0;
    for (const auto& c : kCells) size += c.size() + 1;
    f << "CELLS " << kCells.size() << " " << size << "\n";
    for (const auto& c : kCells) {
        f << c.size();
        for (int v : c) f << " " << v;
        f << "\n";
    }
    f << "CELL_TYPES " << kTypes.size() << "\n";
    for (int t : kTypes) f << t << "\n";
    f << "POINT_DATA " << kPoints << "\nSCALARS p float\nLOOKUP_TABLE default\n";
    for (int p = 0; p < kPoints; ++p) f << 0.5 * p << "\n";
    f << "CELL_DATA " << kCells.size() << "\nSCALARS c double\nLOOKUP_TABLE default\n";
    for (size_t c = 0; c < kCells.size(); ++c) f << 10.0 * double(c) << "\n";
    return f.str();
}

template <typename T>
std::string bigEndian(const std::vector<T>& values) {
    std::string out(values.size() * sizeof(T), '\0');
    std::memcpy(out.data(), values.data(), out.size());
    if constexpr (sizeof(T) > 1)
        if (std::endian::native == std::endian::little)
            for (size_t i = 0; i < out.size(); i += sizeof(T)) std::reverse(out.begin() + long(i), out.begin() + long(i + sizeof(T)));
    return out;
}

std::string legacyBinary51() {
    std::vector<float> points;
    for (int p = 0; p < kPoints; ++p) points.insert(points.end(), {float(p), float(2 * p), float(3 * p)});
    std::vector<int64_t> offsets{0}, connectivity;
    for (const auto& c : kCells) {
        connectivity.insert(connectivity.end(), c.begin(), c.end());
        offsets.push_back(int64_t(connectivity.size()));
    }
    std::vector<float> p(kPoints);
    for (int i = 0; i < kPoints; ++i) p[size_t(i)] = 0.5f * float(i);
    std::vector<double> c;
    for (size_t i = 0; i < kCells.size(); ++i) c.push_back(10.0 * double(i));
    // Appended piece by piece: GCC 12 warns (-Wrestrict, wrongly) on a literal + a temporary string here.
    std::string f = "# vtk DataFile Version 5.1\ncells\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 14 float\n";
    f += bigEndian(points);
    f += "\nMETADATA\nINFORMATION 0\n\nCELLS " + std::to_string(offsets.size()) + " " + std::to_string(connectivity.size());
    f += "\nOFFSETS vtktypeint64\n";
    f += bigEndian(offsets);
    f += "\nCONNECTIVITY vtktypeint64\n";
    f += bigEndian(connectivity);
    f += "\nCELL_TYPES 6\n";
    f += bigEndian(std::vector<int32_t>(kTypes.begin(), kTypes.end()));
    f += "\nPOINT_DATA 14\nSCALARS p float 1\nLOOKUP_TABLE default\n";
    f += bigEndian(p);
    f += "\nCELL_DATA 6\nSCALARS c double 1\nLOOKUP_TABLE default\n";
    f += bigEndian(c);
    return f + "\n";
}

std::string vtuAscii() {
    std::ostringstream f;
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid><Piece NumberOfPoints=\"14\" NumberOfCells=\"6\">\n<PointData Scalars=\"p\">"
         "<DataArray type=\"Float32\" Name=\"p\" format=\"ascii\">";
    for (int p = 0; p < kPoints; ++p) f << 0.5 * p << " ";
    f << "</DataArray></PointData>\n<CellData><DataArray type=\"Float64\" Name=\"c\" format=\"ascii\">";
    for (size_t c = 0; c < kCells.size(); ++c) f << 10.0 * double(c) << " ";
    f << "</DataArray></CellData>\n<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">";
    for (int p = 0; p < kPoints; ++p) f << p << " " << 2 * p << " " << 3 * p << " ";
    f << "</DataArray></Points>\n<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">";
    size_t end = 0;
    std::string offsets;
    for (const auto& c : kCells) {
        for (int v : c) f << v << " ";
        offsets += std::to_string(end += c.size()) + " ";
    }
    f << "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << offsets
      << "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">";
    for (int t : kTypes) f << t << " ";
    f << "</DataArray></Cells>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    return f.str();
}

void checkGrid(const UnstructuredMesh& mesh) {
    REQUIRE(mesh.positions.size() == kPoints);
    CHECK(mesh.positions[5] == glm::vec3(5, 10, 15));
    CHECK(mesh.cellType == std::vector<uint8_t>{10, 12, 13, 14, 12, 10});  // voxel as hexahedron, quadratic by corners
    CHECK(mesh.cellIndex == std::vector<uint32_t>{0, 4, 12, 18, 23, 31});
    const std::vector<uint32_t> voxel(mesh.index.begin() + 23, mesh.index.begin() + 31);
    CHECK(voxel == std::vector<uint32_t>{0, 1, 3, 2, 4, 5, 7, 6});  // VTK's voxel order turned into the hexahedron's
    CHECK(std::vector<uint32_t>(mesh.index.begin() + 31, mesh.index.end()) == std::vector<uint32_t>{4, 5, 6, 7});
    CHECK(mesh.index.size() == 35);
    REQUIRE(mesh.warnings.size() == 1);
    CHECK(mesh.warnings[0].find("1 quadratic cells") == 0);
    CHECK(mesh.fieldName == "p");
    CHECK(!mesh.cellCentered);
    CHECK(mesh.values[13] == 6.5f);
}

}  // namespace

TEST_CASE("VTK unstructured grids: legacy ASCII, legacy 5.1 binary and XML read cell for cell") {
    TempFolder dir;
    for (const auto& [name, text] : {std::pair{"ascii.vtk", legacyAscii()}, std::pair{"binary51.vtk", legacyBinary51()},
                                     std::pair{"grid.vtu", vtuAscii()}}) {
        CAPTURE(name);
        const std::filesystem::path file = writeText(dir / name, text);
        CHECK(isVtkUnstructuredFile(file));
        checkGrid(readVtkUnstructured(file));
        const UnstructuredMesh cells = readVtkUnstructured(file, {"c"});
        CHECK(cells.cellCentered);
        CHECK(cells.values == std::vector<float>{0, 10, 20, 30, 40, 50});
    }
    CHECK(!isVtkUnstructuredFile(writeText(dir / "points.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n")));
}

TEST_CASE("hostile VTK unstructured grids are refused naming the cell or vertex") {
    TempFolder dir;
    const std::string good = legacyAscii();
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        return text.replace(at, from.size(), to);
    };
    struct Case {
        std::string name, text, expected;
    };
    for (const Case& c : {Case{"index.vtk", replaced("6 1 2 3 4 5 6\n", "6 1 2 3 4 5 99\n"), "cell 2 names vertex 99 of 14"},
                          Case{"polyhedron.vtk", replaced("CELL_TYPES 6\n10\n12\n", "CELL_TYPES 6\n10\n42\n"),
                               "cell 1 is a polyhedron (VTK type 42)"},
                          Case{"triangle.vtk", replaced("CELL_TYPES 6\n10\n", "CELL_TYPES 6\n5\n"), "cell 0 is a triangle (VTK type 5)"},
                          Case{"short.vtk", replaced("CELL_TYPES 6\n10\n12\n13\n", "CELL_TYPES 6\n10\n12\n12\n"),
                               "cell 2 (VTK cell type 12) lists 6 vertices, fewer than its 8"},
                          Case{"nan.vtk", replaced("5 10 15\n", "5 nan 15\n"), "point 5 has a coordinate that is NaN"},
                          Case{"count.vtk", replaced("CELL_TYPES 6\n", "CELL_TYPES 5\n"), "unknown keyword '24'"},
                          Case{"field.vtk", replaced("6.5\n", "inf\n"), "array 'p' has 1 values that are NaN, infinite or beyond float, the first at point 13"}}) {
        CAPTURE(c.name);
        CHECK_THROWS_WITH_AS(readVtkUnstructured(writeText(dir / c.name, c.text)), doctest::Contains(c.expected.c_str()), VolumeError);
    }
    CHECK_THROWS_WITH_AS(readVtkUnstructured(writeText(dir / "g.vtu", vtuAscii()), {"absent"}),
                         doctest::Contains("no array 'absent' (arrays: point 'p', cell 'c')"), VolumeError);
}

// Debian's meshio reads the file: points, linear cells by kind, the sum of every cell's corner indices,
// and the named array's sum, min and max ("skip" where it cannot).
std::string meshioSummary(const std::filesystem::path& file, const std::string& array, bool cellData) {
    const std::string script =
        "import sys\n"
        "try:\n import meshio, numpy as np\nexcept Exception:\n print('skip'); sys.exit()\n"
        "m = meshio.read(sys.argv[1])\n"
        "kinds = {'tetra': 0, 'tetra10': 0, 'hexahedron': 1, 'hexahedron20': 1, 'wedge': 2, 'wedge15': 2, 'pyramid': 3, 'pyramid13': 3}\n"
        "corners = [4, 8, 6, 5]\ncounts = [0, 0, 0, 0]\ncornerSum = 0\n"
        "for b in m.cells:\n k = kinds[b.type]; counts[k] += len(b.data); cornerSum += int(b.data[:, :corners[k]].sum())\n"
        "v = np.concatenate([np.asarray(x).ravel() for x in m.cell_data[sys.argv[2]]]) if sys.argv[3] == '1' else "
        "np.asarray(m.point_data[sys.argv[2]]).ravel()\n"
        "print(len(m.points), *counts, cornerSum, '%.9g %.9g %.9g' % (v.astype(np.float64).sum(), v.min(), v.max()))\n";
    const TempFolder dir;
    const std::filesystem::path py = writeText(dir / "meshio_summary.py", script);
    std::string arguments = "'";  // appended piece by piece: see legacyBinary51
    arguments += py.string();
    arguments += "' '";
    arguments += file.string();
    arguments += "' '";
    arguments += array;
    arguments += cellData ? "' 1" : "' 0";
    const ProgramRun run = runProgram("/usr/bin/python3", arguments);
    return run.output.substr(0, run.output.find_last_not_of("\n") + 1);
}

std::string rippleSummary(const std::filesystem::path& file, const std::string& array) {
    const UnstructuredMesh mesh = readVtkUnstructured(file, {array});
    uint64_t counts[4] = {}, cornerSum = 0;
    for (size_t c = 0; c < mesh.cellType.size(); ++c) ++counts[mesh.cellType[c] == 10 ? 0 : mesh.cellType[c] == 12 ? 1 : mesh.cellType[c] == 13 ? 2 : 3];
    for (uint32_t i : mesh.index) cornerSum += i;
    const double sum = std::accumulate(mesh.values.begin(), mesh.values.end(), 0.0);
    char line[200];
    std::snprintf(line, sizeof line, "%zu %llu %llu %llu %llu %llu %.9g %.9g %.9g", mesh.positions.size(),
                  (unsigned long long)counts[0], (unsigned long long)counts[1], (unsigned long long)counts[2],
                  (unsigned long long)counts[3], (unsigned long long)cornerSum, sum, double(mesh.minValue), double(mesh.maxValue));
    return line;
}

TEST_CASE("the shared VTK unstructured grids agree with meshio, or with what they declare") {
    const std::filesystem::path vtk = std::filesystem::path(RIPPLE_DATA_DIR) / "vtk";
    if (!std::filesystem::exists(vtk / "kiefer.vtu")) {
        MESSAGE("skipped: " << vtk.string() << " is absent");
        return;
    }
    struct Case {
        const char* file;
        const char* array;       // as Ripple names it
        const char* meshioName;  // as meshio does (legacy names keep their %20)
        bool cellData;
        // notch_stress.vtk lists 20 vertices under the linear hexahedron type: its first 8 are the corners (the
        // other 12 are exactly their edges' midpoints: checked), but meshio takes the last 8, so the corner
        // sums cannot agree there.
        bool sameCorners = true;
    };
    for (const Case& c : {Case{"kiefer.vtu", "Equivalent (von-Mises) Stress (psi)", "Equivalent (von-Mises) Stress (psi)", true},
                          Case{"QuadraticTetra.vtu", "DistanceToCenter", "DistanceToCenter", false},
                          Case{"notch_stress.vtk", "Nodal Stress-0", "Nodal%20Stress-0", false, false}}) {
        CAPTURE(c.file);
        const std::string expected = meshioSummary(vtk / c.file, c.meshioName, c.cellData);
        if (expected == "skip") {
            MESSAGE("meshio is not installed (python3-meshio): " << c.file << " compared with nothing");
            continue;
        }
        const std::string ours = rippleSummary(vtk / c.file, c.array);
        // Sums of float values summed in another order agree to about 1e-7 relative: compare numerically.
        std::istringstream a(ours), b(expected);
        for (int field = 0; field < 9; ++field) {
            double x = 0, y = 0;
            REQUIRE_MESSAGE(bool(a >> x), ours);
            REQUIRE_MESSAGE(bool(b >> y), expected);
            CAPTURE(field);
            if (field == 5 && !c.sameCorners) continue;
            if (field < 6) CHECK(x == y);  // counts and the corner index sum: exact
            else CHECK(x == doctest::Approx(y).epsilon(1e-6));
        }
    }
    // notch_stress.vtk's "Nodal Stress-normed" is NaN at 9,180 of its 12,717 points (meshio reads the same): refused.
    CHECK_THROWS_WITH_AS(readVtkUnstructured(vtk / "notch_stress.vtk", {"Nodal Stress-normed"}),
                         doctest::Contains("has 9180 values that are NaN, infinite or beyond float, the first at point 1013"),
                         VolumeError);
    // meshio 5 cannot read can.vtu (an appended array's offset it does not find): the file's own declarations.
    const UnstructuredMesh can = readVtkUnstructured(vtk / "can.vtu", {"EQPS"});
    CHECK(can.positions.size() == 6724);  // NumberOfPoints
    CHECK(can.cellType == std::vector<uint8_t>(4800, 12));  // NumberOfCells, all hexahedra
    CHECK(can.cellCentered);
    CHECK(can.minValue == doctest::Approx(0.021583130583));  // RangeMin
    CHECK(can.maxValue == doctest::Approx(2.8939416409));    // RangeMax
    const UnstructuredMesh displacement = readVtkUnstructured(vtk / "can.vtu", {"DISPL"});
    CHECK(displacement.minValue == doctest::Approx(2.4611168269));  // the magnitude's RangeMin
    CHECK(displacement.maxValue == doctest::Approx(18.594444351));
}
