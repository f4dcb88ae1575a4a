// VTK unstructured grids, XML and legacy (see VtkUnstructuredFile.h), read through VtkArrays.h.
#include "io/vtk/VtkUnstructuredFile.h"

#include "io/FileRead.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace ripple::apps {

namespace {

using namespace vtk;

// What Ripple makes of a VTK cell type: the linear cell it is read as, its corner count, and how many
// vertices a cell of the type lists (quadratic cells list their mid-edge nodes after the corners).
struct CellKind {
    uint8_t linear = 0;
    uint32_t corners = 0, nodes = 0;
    bool quadratic = false;
};

std::optional<CellKind> cellKind(uint32_t type) {
    switch (type) {
    case 10: return CellKind{10, 4, 4, false};   // tetrahedron
    case 11: return CellKind{12, 8, 8, false};   // voxel: a hexahedron with its own vertex order
    case 12: return CellKind{12, 8, 8, false};   // hexahedron
    case 13: return CellKind{13, 6, 6, false};   // wedge
    case 14: return CellKind{14, 5, 5, false};   // pyramid
    case 24: return CellKind{10, 4, 10, true};   // quadratic tetrahedron
    case 25: return CellKind{12, 8, 20, true};   // quadratic hexahedron
    case 26: return CellKind{13, 6, 15, true};   // quadratic wedge
    case 27: return CellKind{14, 5, 13, true};   // quadratic pyramid
    case 29: return CellKind{12, 8, 27, true};   // triquadratic hexahedron
    case 32: return CellKind{13, 6, 18, true};   // biquadratic quadratic wedge
    case 33: return CellKind{12, 8, 24, true};   // biquadratic quadratic hexahedron
    default: return std::nullopt;
    }
}

std::string cellTypeName(uint32_t type) {
    switch (type) {
    case 1: return "a vertex (VTK type 1)";
    case 2: return "a poly-vertex (VTK type 2)";
    case 3: return "a line (VTK type 3)";
    case 4: return "a poly-line (VTK type 4)";
    case 5: return "a triangle (VTK type 5)";
    case 6: return "a triangle strip (VTK type 6)";
    case 7: return "a polygon (VTK type 7)";
    case 8: return "a pixel (VTK type 8)";
    case 9: return "a quad (VTK type 9)";
    case 21: return "a quadratic edge (VTK type 21)";
    case 22: return "a quadratic triangle (VTK type 22)";
    case 23: return "a quadratic quad (VTK type 23)";
    case 42: return "a polyhedron (VTK type 42)";
    case 255: return "a VTK cell type outside 0..254";
    default: return "VTK cell type " + std::to_string(type);
    }
}

// The grid as stored: points, each cell's vertex list (start offsets with one past the end), types, arrays.
struct StoredGrid {
    std::vector<double> points;          // x, y, z per point
    std::vector<double> offsets;         // cells + 1 entries
    std::vector<double> connectivity;
    std::vector<double> types;
    std::vector<StoredArray> arrays;
    std::string activeScalars;
};

StoredGrid readXmlGrid(const std::filesystem::path& file, const std::string& text) {
    const XmlDocument xml(file, text, "UnstructuredGrid");
    const pugi::xml_node grid = xml.root().child("UnstructuredGrid");
    if (!grid) fail(file, "no <UnstructuredGrid> element");
    const auto pieces = grid.children("Piece");
    if (std::distance(pieces.begin(), pieces.end()) != 1)
        fail(file, "an UnstructuredGrid of several pieces is not supported (one piece is)");
    const pugi::xml_node piece = grid.child("Piece");
    const uint64_t points = piece.attribute("NumberOfPoints").as_ullong(0), cells = piece.attribute("NumberOfCells").as_ullong(0);
    if (points > kMaxVoxels || cells > kMaxVoxels) fail(file, "more than 2^31 points or cells");
    StoredGrid out;
    const pugi::xml_node pointArray = piece.child("Points").child("DataArray");
    if (!pointArray) fail(file, "no <Points> array");
    out.points = arrayValues(file, xml.array(pointArray, "point", points));
    if (pointArray.attribute("NumberOfComponents").as_uint(1) != 3) fail(file, "its points do not have 3 components");
    const auto cellArray = [&](const char* name) {
        const pugi::xml_node node = piece.child("Cells").find_child_by_attribute("DataArray", "Name", name);
        if (!node) fail(file, std::string("no '") + name + "' array in <Cells>");
        return node;
    };
    // XML offsets are each cell's end; the connectivity's length is the last of them.
    const std::vector<double> ends = arrayValues(file, xml.array(cellArray("offsets"), "cell", cells));
    out.offsets.assign(1, 0.0);
    out.offsets.insert(out.offsets.end(), ends.begin(), ends.end());
    const double connectivity = out.offsets.back();
    if (!(connectivity >= 0 && connectivity <= double(kMaxVoxels) * 27)) fail(file, "its last cell offset is out of range");
    out.connectivity = arrayValues(file, xml.array(cellArray("connectivity"), "cell", uint64_t(connectivity)));
    out.types = arrayValues(file, xml.array(cellArray("types"), "cell", cells));
    for (const auto& [section, association, tuples] :
         {std::tuple{"PointData", "point", points}, std::tuple{"CellData", "cell", cells}}) {
        const pugi::xml_node data = piece.child(section);
        if (std::string(association) == "point") out.activeScalars = data.attribute("Scalars").value();
        for (const pugi::xml_node array : data.children("DataArray")) out.arrays.push_back(xml.array(array, association, tuples));
    }
    return out;
}

StoredGrid readLegacyGrid(const std::filesystem::path& file, const std::string& bytes) {
    LegacyReader in(file, bytes);
    const LegacyHeader header = readLegacyHeader(in, file);
    if (header.dataset != "UNSTRUCTURED_GRID") fail(file, "a legacy " + header.dataset + " data set, not an UNSTRUCTURED_GRID");
    LegacyAttributes attributes(in, file, header.binary);
    StoredGrid out;
    bool havePoints = false, haveCells = false, haveTypes = false;
    const auto array = [&](const std::string& type, uint64_t count, const char* what) {
        StoredArray a;
        a.info.name = what;
        a.info.type = type;
        a.info.tuples = count;
        if (typeInfo(type).size == 0) fail(file, std::string(what) + " of unknown type '" + type + "'");
        in.data(a, header.binary, count);
        return arrayValues(file, a);
    };
    for (std::string key = in.word(); !key.empty(); key = in.done() ? "" : in.word()) {
        if (key == "POINTS") {
            const uint64_t n = in.count("POINTS");
            if (n > kMaxVoxels) fail(file, "POINTS " + std::to_string(n) + " is more than 2^31");
            const std::string type = in.word();
            out.points = array(type, n * 3, "POINTS");
            havePoints = true;
        } else if (key == "CELLS") {
            const uint64_t first = in.count("CELLS"), second = in.count("CELLS size");
            if (first > kMaxVoxels + 1 || second > kMaxVoxels * 28) fail(file, "CELLS " + std::to_string(first) + " is too large");
            if (header.version >= 5.1 - 1e-9) {  // OFFSETS (cells + 1 entries) and CONNECTIVITY arrays
                if (in.word() != "OFFSETS") fail(file, "CELLS of a version 5.1 file without its OFFSETS array");
                out.offsets = array(in.word(), first, "OFFSETS");
                if (in.word() != "CONNECTIVITY") fail(file, "CELLS without its CONNECTIVITY array");
                out.connectivity = array(in.word(), second, "CONNECTIVITY");
            } else {  // each cell as its vertex count and its vertices
                const std::vector<double> list = array("int", second, "CELLS");
                out.offsets.assign(1, 0.0);
                for (uint64_t at = 0, c = 0; c < first; ++c) {
                    if (at >= list.size()) fail(file, "the CELLS list ends at cell " + std::to_string(c) + " of " + std::to_string(first));
                    const double n = list[at++];
                    if (!(n >= 0 && n <= double(list.size() - at))) fail(file, "cell " + std::to_string(c) + " runs past the CELLS list");
                    out.connectivity.insert(out.connectivity.end(), list.begin() + long(at), list.begin() + long(at + uint64_t(n)));
                    out.offsets.push_back(double(out.connectivity.size()));
                    at += uint64_t(n);
                }
            }
            haveCells = true;
        } else if (key == "CELL_TYPES") {
            out.types = array("int", in.count("CELL_TYPES"), "CELL_TYPES");
            haveTypes = true;
        } else if (!attributes.take(key)) {
            fail(file, "unknown keyword '" + key + "'");
        }
    }
    if (!havePoints || !haveCells || !haveTypes) fail(file, "an UNSTRUCTURED_GRID needs POINTS, CELLS and CELL_TYPES");
    out.arrays = std::move(attributes.arrays);
    out.activeScalars = attributes.activeScalars;
    return out;
}

bool isVtu(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".vtu";
}

StoredGrid readGrid(const std::filesystem::path& file) {
    const std::string bytes = readRegularFile(file, kMaxVtkFileBytes, "");
    try {
        return isVtu(file) ? readXmlGrid(file, bytes) : readLegacyGrid(file, bytes);
    } catch (const std::bad_alloc&) {
        fail(file, "too large to read");
    }
}

}  // namespace

uint32_t linearCellCorners(uint8_t type) {
    const std::optional<CellKind> kind = cellKind(type);
    return kind && !kind->quadratic && kind->linear == type ? kind->corners : 0;
}

bool isVtkUnstructuredFile(const std::filesystem::path& file) {
    if (isVtu(file)) return true;
    if (!isVtkImageFile(file) || file.extension() == ".vti") return false;
    // A legacy file: its DATASET line, within the first lines.
    uint64_t size = 0;
    std::string error;
    const FileDescriptor fd = openRegularFile(file, false, size, error);
    if (fd.get() < 0) return false;
    std::string head(4096, '\0');
    const ssize_t n = ::pread(fd.get(), head.data(), head.size(), 0);
    head.resize(n > 0 ? size_t(n) : 0);
    const size_t dataset = head.find("DATASET");
    return dataset != std::string::npos && head.compare(dataset, 25, "DATASET UNSTRUCTURED_GRID") == 0;
}

std::vector<VtkArrayInfo> listVtkUnstructuredArrays(const std::filesystem::path& file) {
    std::vector<VtkArrayInfo> list;
    for (const StoredArray& a : readGrid(file).arrays) list.push_back(a.info);
    return list;
}

UnstructuredMesh readVtkUnstructured(const std::filesystem::path& file, const VtkFieldChoice& choice) {
    const StoredGrid grid = readGrid(file);
    const uint64_t points = grid.points.size() / 3, cells = grid.types.size();
    if (grid.offsets.size() != cells + 1)
        fail(file, std::to_string(grid.offsets.size() - 1) + " cell offsets for " + std::to_string(cells) + " cell types");
    UnstructuredMesh mesh;
    mesh.positions.resize(points);
    for (uint64_t p = 0; p < points; ++p) {
        for (int a = 0; a < 3; ++a) {
            const double v = grid.points[p * 3 + uint64_t(a)];
            if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
                fail(file, "point " + std::to_string(p) + " has a coordinate that is NaN, infinite or beyond float");
            mesh.positions[p][a] = float(v);
        }
    }
    uint64_t quadratic = 0, overlong = 0;
    mesh.cellIndex.reserve(cells);
    mesh.cellType.reserve(cells);
    for (uint64_t c = 0; c < cells; ++c) {
        // A hostile type may be negative, huge or NaN: only a small whole number is converted.
        const double storedType = grid.types[c];
        const uint32_t type = storedType >= 0 && storedType < 256 ? uint32_t(storedType) : 255;
        const std::optional<CellKind> kind = cellKind(type);
        if (!kind) fail(file, "cell " + std::to_string(c) + " is " + cellTypeName(type) +
                                  "; Ripple reads tetrahedra, hexahedra, wedges, pyramids and voxels, linear or quadratic");
        const double begin = grid.offsets[c], end = grid.offsets[c + 1];
        if (!(begin >= 0 && end >= begin && end <= double(grid.connectivity.size())))
            fail(file, "cell " + std::to_string(c) + "'s vertices run past the connectivity");
        if (end - begin < double(kind->nodes))
            fail(file, "cell " + std::to_string(c) + " (" + cellTypeName(type) + ") lists " +
                           std::to_string(uint64_t(end - begin)) + " vertices, fewer than its " + std::to_string(kind->nodes));
        // Some writers list a quadratic cell's nodes under the linear type (notch_stress.vtk: type 12 with 20
        // vertices); its corners come first all the same.
        overlong += end - begin > double(kind->nodes) ? 1 : 0;
        static constexpr uint32_t voxelOrder[8] = {0, 1, 3, 2, 4, 5, 7, 6};
        mesh.cellIndex.push_back(uint32_t(mesh.index.size()));
        mesh.cellType.push_back(kind->linear);
        for (uint32_t k = 0; k < kind->corners; ++k) {
            const double vertex = grid.connectivity[uint64_t(begin) + (type == 11 ? voxelOrder[k] : k)];
            if (!(vertex >= 0 && vertex < double(points))) {
                char text[32];
                std::snprintf(text, sizeof text, "%.17g", vertex);
                fail(file, "cell " + std::to_string(c) + " names vertex " + text + " of " + std::to_string(points));
            }
            mesh.index.push_back(uint32_t(vertex));
        }
        quadratic += kind->quadratic ? 1 : 0;
    }
    if (overlong > 0)
        mesh.warnings.push_back(std::to_string(overlong) + " cells list more vertices than their type has; read through "
                                "their first ones, the corners");
    if (quadratic > 0)
        mesh.warnings.push_back(std::to_string(quadratic) + " quadratic cells read through their corner vertices: their "
                                "mid-edge nodes are left out, and the field is interpolated linearly within them");

    // The field: the chosen array, the active scalars, the first point array, the first cell array.
    const auto first = [&](const std::string& association, const std::string& name) -> const StoredArray* {
        for (const StoredArray& a : grid.arrays)
            if (a.info.association == association && (name.empty() || a.info.name == name)) return &a;
        return nullptr;
    };
    const StoredArray* chosen = nullptr;
    if (!choice.name.empty()) {
        chosen = first("point", choice.name);
        if (!chosen) chosen = first("cell", choice.name);
    } else {
        if (!grid.activeScalars.empty()) chosen = first("point", grid.activeScalars);
        if (!chosen) chosen = first("point", "");
        if (!chosen) chosen = first("cell", "");
    }
    if (!chosen) {
        if (!choice.name.empty()) {
            std::string names;
            for (const StoredArray& a : grid.arrays) names += (names.empty() ? "" : ", ") + a.info.association + " '" + a.info.name + "'";
            fail(file, "no array '" + choice.name + "' (arrays: " + (names.empty() ? "none" : names) + ")");
        }
        return mesh;  // geometry only
    }
    mesh.fieldName = chosen->info.name;
    mesh.cellCentered = chosen->info.association == "cell";
    const uint64_t tuples = mesh.cellCentered ? cells : points;
    if (chosen->info.tuples != tuples)
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.tuples) + " tuples for " + std::to_string(tuples) +
                       (mesh.cellCentered ? " cells" : " points"));
    if (choice.component >= int(chosen->info.components))
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.components) + " components; component " +
                       std::to_string(choice.component) + " asked for");
    const std::vector<double> all = arrayValues(file, *chosen);
    const uint32_t n = chosen->info.components;
    mesh.values.resize(tuples);
    uint64_t nonFinite = 0, firstNonFinite = 0;
    for (uint64_t i = 0; i < tuples; ++i) {
        double v = 0;
        if (choice.component >= 0) {
            v = all[i * n + uint64_t(choice.component)];
        } else if (n == 1) {
            v = all[i];
        } else {
            for (uint32_t k = 0; k < n; ++k) v += all[i * n + k] * all[i * n + k];
            v = std::sqrt(v);
        }
        if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
            firstNonFinite = nonFinite++ == 0 ? i : firstNonFinite;
        mesh.values[i] = float(v);
    }
    if (nonFinite > 0)
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(nonFinite) + " values that are NaN, infinite or beyond "
                       "float, the first at " + (mesh.cellCentered ? "cell " : "point ") + std::to_string(firstNonFinite));
    if (!mesh.values.empty()) {
        const auto [lo, hi] = std::minmax_element(mesh.values.begin(), mesh.values.end());
        mesh.minValue = *lo;
        mesh.maxValue = *hi;
    }
    return mesh;
}

}  // namespace ripple::apps
