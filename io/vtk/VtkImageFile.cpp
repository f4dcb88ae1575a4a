// VTK image data, XML and legacy (see VtkImageFile.h), read through the array machinery of VtkArrays.h.
#include "io/vtk/VtkImageFile.h"

#include "io/FileRead.h"
#include "io/vtk/VtkArrays.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace ripple::apps {

namespace {

using namespace vtk;

struct ImageGrid {
    glm::uvec3 dims{0};
    glm::vec3 origin{0.0f}, spacing{1.0f};
    std::vector<StoredArray> arrays;
    std::string activeScalars;
};

ImageGrid readXmlImage(const std::filesystem::path& file, const std::string& text) {
    const XmlDocument xml(file, text, "ImageData");
    const pugi::xml_node& root = xml.root();
    const pugi::xml_node image = root.child("ImageData");
    if (!image) fail(file, "no <ImageData> element");
    const std::vector<double> extent = numbersIn(image.attribute("WholeExtent").value());
    if (extent.size() != 6) fail(file, "WholeExtent is not six integers");
    ImageGrid grid;
    for (int a = 0; a < 3; ++a) {
        const double n = extent[size_t(2 * a + 1)] - extent[size_t(2 * a)] + 1;
        if (!(n >= 1 && n <= double(kMaxVoxels))) fail(file, "WholeExtent spans no samples along an axis");
        grid.dims[a] = uint32_t(n);
    }
    const std::vector<double> origin = numbersIn(image.attribute("Origin").as_string("0 0 0"));
    const std::vector<double> spacing = numbersIn(image.attribute("Spacing").as_string("1 1 1"));
    if (origin.size() != 3 || spacing.size() != 3) fail(file, "Origin and Spacing need three numbers each");
    const std::vector<double> direction = numbersIn(image.attribute("Direction").as_string("1 0 0 0 1 0 0 0 1"));
    if (direction != std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1})
        fail(file, "a Direction other than the identity (a rotated grid) is not supported");
    for (int a = 0; a < 3; ++a) {
        grid.origin[a] = float(origin[size_t(a)]);
        grid.spacing[a] = float(spacing[size_t(a)]);
    }
    const auto pieces = image.children("Piece");
    if (std::distance(pieces.begin(), pieces.end()) != 1) fail(file, "an ImageData of several pieces is not supported (one piece is)");
    const pugi::xml_node piece = image.child("Piece");
    const uint64_t points = uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    const uint64_t cells = uint64_t(std::max(grid.dims.x - 1, 1u)) * std::max(grid.dims.y - 1, 1u) * std::max(grid.dims.z - 1, 1u);
    for (const char* association : {"PointData", "CellData"}) {
        const pugi::xml_node data = piece.child(association);
        if (std::string(association) == "PointData") grid.activeScalars = data.attribute("Scalars").value();
        for (const pugi::xml_node array : data.children("DataArray")) {
            StoredArray a = xml.array(array, std::string(association) == "PointData" ? "point" : "cell",
                                      std::string(association) == "PointData" ? points : cells);
            grid.arrays.push_back(std::move(a));
        }
    }
    return grid;
}

ImageGrid readLegacyImage(const std::filesystem::path& file, const std::string& bytes) {
    LegacyReader in(file, bytes);
    const LegacyHeader header = readLegacyHeader(in, file);
    if (header.dataset != "STRUCTURED_POINTS")
        fail(file, "a legacy " + header.dataset + " data set; Ripple reads STRUCTURED_POINTS here");
    LegacyAttributes attributes(in, file, header.binary);
    ImageGrid grid;
    bool haveDims = false;
    for (std::string key = in.word(); !key.empty(); key = in.done() ? "" : in.word()) {
        if (key == "DIMENSIONS") {
            for (int a = 0; a < 3; ++a) {
                const uint64_t n = in.count("DIMENSIONS");
                if (n < 1 || n > kMaxVoxels) fail(file, "DIMENSIONS " + std::to_string(n) + " along an axis");
                grid.dims[a] = uint32_t(n);
            }
            haveDims = true;
        } else if (key == "SPACING" || key == "ASPECT_RATIO") {
            for (int a = 0; a < 3; ++a) grid.spacing[a] = float(in.number(key));
        } else if (key == "ORIGIN") {
            for (int a = 0; a < 3; ++a) grid.origin[a] = float(in.number(key));
        } else if (!attributes.take(key)) {
            fail(file, "unknown keyword '" + key + "'");
        }
    }
    grid.arrays = std::move(attributes.arrays);
    grid.activeScalars = attributes.activeScalars;
    if (!haveDims) fail(file, "no DIMENSIONS");
    return grid;
}

ImageGrid readImage(const std::filesystem::path& file) {
    const std::string bytes = readRegularFile(file, kMaxVtkFileBytes, "");
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    try {
        return extension == ".vti" ? readXmlImage(file, bytes) : readLegacyImage(file, bytes);
    } catch (const std::bad_alloc&) {
        fail(file, "too large to read");
    }
}

}  // namespace

bool isVtkImageFile(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".vti" || extension == ".vtk";
}

std::vector<VtkArrayInfo> listVtkArrays(const std::filesystem::path& file) {
    std::vector<VtkArrayInfo> list;
    for (const StoredArray& a : readImage(file).arrays) list.push_back(a.info);
    return list;
}

namespace {

// The array `choice` names among those of `association` ("point" or "cell"): by name, else the active
// scalars (point arrays), else the first. Checks its tuple count and the component asked for.
const StoredArray& chooseArray(const std::filesystem::path& file, const ImageGrid& grid, const VtkFieldChoice& choice,
                               const std::string& association, uint64_t tuples) {
    const std::string wanted = !choice.name.empty() ? choice.name : association == "point" ? grid.activeScalars : "";
    const StoredArray* chosen = nullptr;
    for (const StoredArray& a : grid.arrays)
        if (a.info.association == association && (wanted.empty() || a.info.name == wanted)) {
            chosen = &a;
            break;
        }
    if (!chosen) {
        std::string names;
        for (const StoredArray& a : grid.arrays) names += (names.empty() ? "" : ", ") + a.info.association + " '" + a.info.name + "'";
        fail(file, (wanted.empty() ? "no " + association + " array" : "no " + association + " array '" + wanted + "'") +
                       " (arrays: " + (names.empty() ? "none" : names) + ")");
    }
    if (chosen->info.tuples != tuples)
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.tuples) + " tuples for " +
                       std::to_string(tuples) + " " + association + "s");
    if (choice.component >= int(chosen->info.components))
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.components) + " components; component " +
                       std::to_string(choice.component) + " asked for");
    return *chosen;
}

// Tuples first .. first + out.size() of `all` (`components` per tuple) as scalars: the chosen component, or
// the magnitude. Values that are not finite or beyond float are refused.
void scalarsOf(const std::filesystem::path& file, const StoredArray& array, const std::vector<double>& all, uint64_t first,
               int component, std::vector<float>& out) {
    const uint32_t c = array.info.components;
    uint64_t nonFinite = 0;
    for (uint64_t i = 0; i < out.size(); ++i) {
        const double* tuple = all.data() + (first + i) * c;
        double v = 0.0;
        if (component >= 0) {
            v = tuple[component];
        } else if (c == 1) {
            v = tuple[0];
        } else {
            for (uint32_t k = 0; k < c; ++k) v += tuple[k] * tuple[k];
            v = std::sqrt(v);
        }
        if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max())) ++nonFinite;
        out[i] = float(v);
    }
    if (nonFinite > 0) fail(file, "array '" + array.info.name + "' has " + std::to_string(nonFinite) + " values that are NaN, infinite or beyond float");
}

}  // namespace

VolumeData readVtkImageVolume(const std::filesystem::path& file, const VtkFieldChoice& choice, VolumeSlab slab) {
    ImageGrid grid = readImage(file);
    const uint64_t points = uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    if (points > kMaxVoxels) fail(file, std::to_string(points) + " samples is more than the 2^31 Ripple reads");
    const StoredArray& chosen = chooseArray(file, grid, choice, "point", points);
    const std::vector<double> all = arrayValues(file, chosen);
    // The slab's sample planes (the same split as the raw and NRRD readers: each slab keeps its cells' planes).
    const uint64_t cellsZ = grid.dims.z - 1;
    if (slab.count == 0 || slab.index >= slab.count || cellsZ < slab.count)
        fail(file, std::to_string(grid.dims.z) + " sample planes along z cannot be split into " +
                       std::to_string(slab.count) + " slabs (each needs one cell)");
    const uint32_t zFirst = uint32_t(cellsZ * slab.index / slab.count);
    const uint32_t zLast = uint32_t(cellsZ * (slab.index + 1) / slab.count);
    VolumeData out;
    out.wholeDims = grid.dims;
    out.dims = glm::uvec3(grid.dims.x, grid.dims.y, zLast - zFirst + 1);
    out.zFirst = zFirst;
    out.origin = grid.origin;
    out.spacing = grid.spacing;
    for (int a = 0; a < 3; ++a)
        if (!(out.spacing[a] > 0.0f && std::isfinite(out.spacing[a]))) fail(file, "its spacing must be positive and finite");
    const uint64_t plane = uint64_t(grid.dims.x) * grid.dims.y;
    out.values.resize(plane * out.dims.z);
    scalarsOf(file, chosen, all, uint64_t(zFirst) * plane, choice.component, out.values);
    const auto [lo, hi] = std::minmax_element(out.values.begin(), out.values.end());
    out.minValue = *lo;
    out.maxValue = *hi;
    return out;
}

VtkImageCells readVtkImageCells(const std::filesystem::path& file, const VtkFieldChoice& choice) {
    const ImageGrid grid = readImage(file);
    VtkImageCells out;
    out.cells = glm::max(grid.dims, 2u) - 1u;
    const uint64_t count = uint64_t(out.cells.x) * out.cells.y * out.cells.z;
    if (count > kMaxVoxels) fail(file, std::to_string(count) + " cells is more than the 2^31 Ripple reads");
    const StoredArray& chosen = chooseArray(file, grid, choice, "cell", count);
    out.name = chosen.info.name;
    out.origin = grid.origin;
    out.spacing = grid.spacing;
    for (int a = 0; a < 3; ++a)
        if (!(out.spacing[a] > 0.0f && std::isfinite(out.spacing[a]))) fail(file, "its spacing must be positive and finite");
    out.values.resize(count);
    scalarsOf(file, chosen, arrayValues(file, chosen), 0, choice.component, out.values);
    return out;
}

}  // namespace ripple::apps
