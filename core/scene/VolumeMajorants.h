// The volumes' macrocell majorants, computed on the device (shaders/volume_majorants.comp) from the voxels
// and transfer-function tables already uploaded: the scene build writes them into the space VolumeTable
// leaves for them, so neither the host nor the upload touches the voxels twice.
#pragma once

#include "core/vk/Buffer.h"
#include "core/vk/Context.h"
#include "shaders/shared/volume.h"

#include <vector>

namespace ripple::core {

struct MajorantGrids {
    double seconds = 0.0;
    uint64_t fineVolumes = 0;  // volumes that use the fine grid
};

// Fills both majorant grids of every record in `volumeData` and chooses each volume's grid: the fine one
// where its majorants, summed over its cells, are at most 1 / kFineGridGain of the coarse majorants
// over the same cells. A transfer function whose extinction is high in a narrow band of values (a thin
// shell) gives coarse macrocells the band's peak wherever the band passes, so most of their tentative
// collisions are null; a smooth one gains little from the finer grid and keeps the coarse one, whose
// macrocells cost fewer crossings. The choice is written into `records`, which are uploaded again to
// `volumes`. Waits for the device.
inline constexpr double kFineGridGain = 2.0;
MajorantGrids buildMajorantsOnDevice(const vk::Context& context, vk::Buffer& volumes, const vk::Buffer& volumeData,
                                     std::vector<gpu::VolumeRecord>& records);

}  // namespace ripple::core
