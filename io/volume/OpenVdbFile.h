// Reads OpenVDB's files (.vdb) with Debian's libopenvdb and converts a float grid to NanoVDB with NanoVDB's own
// converter (OpenToNanoVDB.h), as the buffer ANARI's nanovdb spatial field takes: the same NanoVdbFile the
// .nvdb reader gives (NanoVdbFile.h), so that everything after the reading is shared.
#pragma once

#include "io/volume/NanoVdbFile.h"

#include <filesystem>
#include <string>

namespace ripple::apps {

// Whether `file` is named as an OpenVDB file (.vdb).
bool isOpenVdbFile(const std::filesystem::path& file);

// The float grid named `gridName` (empty: the file's first float grid). Throws VolumeError naming the file and
// the problem: not an OpenVDB file, no such grid, not a float grid, a grid with no active voxel, or whatever
// OpenVDB's reader reports.
NanoVdbFile readOpenVdbFile(const std::filesystem::path& file, const std::string& gridName = "");

}  // namespace ripple::apps
