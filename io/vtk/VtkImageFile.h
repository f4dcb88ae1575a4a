// Reads VTK's image data as a structured-regular field: XML ImageData (.vti: ascii, base64 or raw appended
// arrays, vtkZLibDataCompressor, UInt32 or UInt64 headers, either byte order) and legacy STRUCTURED_POINTS
// (.vtk: ASCII or big-endian BINARY, file versions 1.0 to 5.1, SPACING or its old name ASPECT_RATIO, FIELD
// blocks). Point arrays by name; vectors by magnitude or one component. No ANARI here.
#pragma once

#include "io/volume/VolumeFile.h"
#include "io/vtk/VtkArrays.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

// Whether `file` is read as VTK image data (its extension is .vti or .vtk, any case).
bool isVtkImageFile(const std::filesystem::path& file);

// Which array to read: by name (empty: the file's active scalars, else its first point array), and for a
// vector, which component (-1: the magnitude).
struct VtkFieldChoice {
    std::string name;
    int component = -1;
};

// The arrays of `file`. Throws VolumeError naming the file and what is wrong.
std::vector<VtkArrayInfo> listVtkArrays(const std::filesystem::path& file);

// The chosen point array of `file` as a field (one value per sample point, x fastest), or one z-slab of it.
// Cell arrays are refused (a structured field's values sit on its points). Throws VolumeError.
VolumeData readVtkImageVolume(const std::filesystem::path& file, const VtkFieldChoice& choice = {},
                              VolumeSlab slab = {});

// The cells of an image and the values of one of its cell arrays (an AMR block: io/vtk/VtkAmrFile.h).
struct VtkImageCells {
    glm::uvec3 cells{0};                // per axis (a flat axis of one sample counts one cell)
    glm::vec3 origin{0.0f}, spacing{1.0f};
    std::string name;                   // the array's
    std::vector<float> values;          // cells.x * cells.y * cells.z, x fastest
};

// The chosen cell array of `file` (by name, else its first cell array; vectors by magnitude or one component).
// Throws VolumeError.
VtkImageCells readVtkImageCells(const std::filesystem::path& file, const VtkFieldChoice& choice = {});

}  // namespace ripple::apps
