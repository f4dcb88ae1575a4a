// Reads VTK unstructured grids of volume cells, as finite-element and CFD codes write them: XML
// UnstructuredGrid (.vtu) and legacy UNSTRUCTURED_GRID (.vtk; version 5.1's OFFSETS/CONNECTIVITY arrays
// and the older cell lists). Tetrahedra, hexahedra, wedges and pyramids (VTK cell types 10, 12, 13, 14) and
// voxels (11, reordered as hexahedra); their quadratic forms (24 to 27) through their corner vertices, with one
// warning that says so; any other cell type is refused by name with the first cell's index. No ANARI here:
// the mesh comes back in the layout of ANARI's unstructured spatial field.
#pragma once

#include "io/vtk/VtkArrays.h"
#include "io/vtk/VtkImageFile.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

// ANARI's KHR_SPATIAL_FIELD_UNSTRUCTURED layout: cell c's corners are index[cellIndex[c] ...] in VTK's
// vertex order for cellType[c]; values are per vertex or per cell.
struct UnstructuredMesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> index;
    std::vector<uint32_t> cellIndex;
    std::vector<uint8_t> cellType;       // 10 tetrahedron, 12 hexahedron, 13 wedge, 14 pyramid
    std::string fieldName;               // the array `values` holds; empty when the file has none
    bool cellCentered = false;
    std::vector<float> values;
    float minValue = 0.0f, maxValue = 0.0f;
    std::vector<std::string> warnings;   // quadratic cells read by their corners, ...
};

// Corners of a cell of the linear types the mesh holds (10, 12, 13, 14); 0 for any other type.
uint32_t linearCellCorners(uint8_t type);

// Whether `file` is an unstructured grid: a .vtu, or a legacy .vtk whose DATASET is UNSTRUCTURED_GRID.
bool isVtkUnstructuredFile(const std::filesystem::path& file);

// The arrays of an unstructured grid file.
std::vector<VtkArrayInfo> listVtkUnstructuredArrays(const std::filesystem::path& file);

// The mesh and the chosen array (by name; empty: the active scalars, else the first point array, else the
// first cell array; a vector by magnitude unless a component is chosen). Indices out of range, cells whose
// vertices run past the connectivity, non-finite positions or values: VolumeError naming the file and the
// first offending cell or vertex.
UnstructuredMesh readVtkUnstructured(const std::filesystem::path& file, const VtkFieldChoice& choice = {});

}  // namespace ripple::apps
