// The volumes the kernels read (shaders/shared/volume.h): each valid Volume of a description becomes a
// VolumeRecord, and its transfer-function table (albedo, extinction), that table's range-maximum table
// and room for its macrocell majorants (zeros, filled on the device: VolumeMajorants.h) are appended to
// one float array. Its voxels go to a buffer of their own (the Scene sets VolumeRecord::voxels). Volumes
// with bad data are skipped and reported, never uploaded.
#pragma once

#include "core/bvh/Aabb.h"
#include "core/scene/SceneDescription.h"
#include "shaders/shared/volume.h"

#include <string>
#include <vector>

namespace ripple::core {

struct VolumeTable {
    std::vector<gpu::VolumeRecord> records;
    std::vector<size_t> sources;          // the description's index of each record's volume
    std::vector<float> data;
    bvh::Aabb bounds;                     // world box of the kept volumes
    std::vector<bvh::Aabb> boxes;         // world box of each kept volume, as records
    uint64_t skipped = 0;
    std::vector<std::string> messages;    // one per skipped volume, naming it and the problem
};

VolumeTable buildVolumeTable(const std::vector<Volume>& volumes);

// Macrocells per axis (of VOLUME_MACROCELL^3 cells) over a field of `dims` voxels (dims - 1 cells).
glm::uvec3 macrocellsPerAxis(glm::uvec3 dims);

// Entries of the transfer-function table for `volume`: the longer of its colour and opacity arrays, at
// least kMinTransferEntries (the arrays are resampled linearly). The colour and the opacity are linear
// between array entries, as the other ANARI devices take them; extinction -ln(1 - opacity) / unitDistance
// is not, so the table samples it finely (for opacity 0 to 1 - 1/e over the range, its own linear
// interpolation is within 6e-6 of the exact curve; steeper close to opacity 1, where it errs high).
constexpr size_t kMinTransferEntries = 256;
size_t transferTableSize(const Volume& volume);

// Levels of the range-maximum table that follows a volume's transfer-function table (shared/volume.h):
// floor(log2(entries)) + 1, so that one level's blocks span at least half of any range of entries.
uint32_t extinctionMaxLevels(size_t entries);

}  // namespace ripple::core
