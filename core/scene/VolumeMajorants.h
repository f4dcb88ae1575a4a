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
    uint64_t cellByCellVolumes = 0;  // volumes whose records got cellByCell = 1
};

// Fills the majorant grid of every structured record in `volumeData` and sets each record's cellByCell: 1 where a
// linearly filtered volume has a macrocell whose majorant times the longest cell edge (in world units)
// reaches VOLUME_REFINE_DEPTH, so that some ray may cross it cell by cell (a cell crossing is at most that
// long). The records are uploaded again to `volumes` when one changed. Waits for the device.
MajorantGrids buildMajorantsOnDevice(const vk::Context& context, vk::Buffer& volumes, const vk::Buffer& volumeData,
                                     std::vector<gpu::VolumeRecord>& records);

}  // namespace ripple::core
