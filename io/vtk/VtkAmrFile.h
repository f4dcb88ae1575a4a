// Reads VTK's AMR data sets as block-structured hierarchies: XML hierarchical box data sets (.vthb: a
// vtkOverlappingAMR or vtkHierarchicalBoxDataSet, file version 1.1, each block an ImageData .vti file with
// its level's spacing and an amr_box of cells) and multiblock sets of image data at several spacings (.vtm:
// each spacing a level, finest smallest; blocks placed by their origins). Cell arrays by name; vectors by
// magnitude or one component. Block files are named relative to the set's folder and confined to it. No
// ANARI here: apps/scene turns the result into an "amr" spatial field.
#pragma once

#include "io/vtk/VtkImageFile.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

// Whether `file` is read as a VTK AMR set (its extension is .vthb, .vth or .vtm, any case).
bool isVtkAmrFile(const std::filesystem::path& file);

// A hierarchy as ANARI's "amr" field takes it: cell (i, j, k) of level l spans
// origin + spacing * cellWidth[l] * ([i, i + 1], [j, j + 1], [k, k + 1]).
struct AmrData {
    glm::vec3 origin{0.0f};
    glm::vec3 spacing{1.0f};               // level 0's cell size
    std::vector<float> cellWidth;          // per level, 1 at level 0, decreasing
    struct Block {
        uint32_t level = 0;
        glm::ivec3 lower{0}, upper{0};     // cells, inclusive, in the level's index space
        std::vector<float> values;         // x fastest
    };
    std::vector<Block> blocks;
    std::string arrayName;
    float minValue = 0.0f, maxValue = 0.0f;
    uint64_t cells = 0;
};

// The arrays of the set's first block. Throws VolumeError.
std::vector<VtkArrayInfo> listVtkAmrArrays(const std::filesystem::path& file);

// The set, with the chosen cell array of every block. Throws VolumeError naming the set or the block file and
// what is wrong: a missing or escaping block file, a block whose cells disagree with its amr_box, spacings
// that are not one level's divided by a common ratio per axis, a block off its level's grid, no cell array.
AmrData readVtkAmr(const std::filesystem::path& file, const VtkFieldChoice& choice = {});

}  // namespace ripple::apps
