// The volumes' macrocell majorants, computed on the device (shaders/volume_majorants.comp) from the voxels
// and transfer-function tables already uploaded: the scene build writes them into the space VolumeTable
// leaves for them, so neither the host nor the upload touches the voxels twice.
#pragma once

#include "core/vk/Context.h"
#include "shaders/shared/volume.h"

#include <span>

namespace ripple::core {

// Fills every record's majorant grid in `volumeData` and waits for the device. Returns the seconds taken.
double buildMajorantsOnDevice(const vk::Context& context, VkDeviceAddress volumes, VkDeviceAddress volumeData,
                              std::span<const gpu::VolumeRecord> records);

}  // namespace ripple::core
