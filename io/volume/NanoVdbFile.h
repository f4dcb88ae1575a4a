// Reads NanoVDB's own files (.nvdb): the first grid of the file's first segment, uncompressed, as the
// buffer ANARI's nanovdb spatial field takes. Sizes are checked against the file before anything is copied;
// the grid itself is checked by the device when the field is committed (core/scene/NanoVdbGrid.h).
#pragma once

#include "io/volume/VolumeFile.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

struct NanoVdbFile {
    std::vector<uint8_t> grid;           // the grid buffer
    std::string name;                    // the grid's name in the file
    glm::dvec3 worldLo{0.0}, worldHi{0.0};  // the box of its active values in world space, as the file states
    float minValue = 0.0f, maxValue = 0.0f;  // of its active values, as its root states
};

// Whether `file` is named as a NanoVDB file (.nvdb).
bool isNanoVdbFile(const std::filesystem::path& file);

// Throws VolumeError naming the file and the problem: not a NanoVDB file (magic), another major version, no
// grid, a compressed file (zip and blosc are not read), not a float grid, sizes that run past the file.
NanoVdbFile readNanoVdbFile(const std::filesystem::path& file);

}  // namespace ripple::apps
