// Dispatches volume_majorants.comp over each volume's macrocells (VolumeMajorants.h).
#include "core/scene/VolumeMajorants.h"

#include "core/vk/ComputePipeline.h"
#include "shaders/volume_majorants.spv.h"

#include <algorithm>
#include <chrono>

namespace ripple::core {

double buildMajorantsOnDevice(const vk::Context& context, VkDeviceAddress volumes, VkDeviceAddress volumeData,
                              std::span<const gpu::VolumeRecord> records) {
    if (records.empty()) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    constexpr uint32_t kWorkgroup = 64;  // volume_majorants.comp's local_size_x
    const vk::ComputePipeline pipeline(context, shaders::volume_majorants, "volume_majorants",
                                       static_cast<uint32_t>(sizeof(gpu::MajorantParams)));
    const uint64_t cellsPerDispatch = uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * kWorkgroup;
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::computeBarrier(cmd);  // after the uploads
        pipeline.bind(cmd);
        for (uint32_t i = 0; i < records.size(); ++i) {
            const uint64_t cells = uint64_t(records[i].macroX) * records[i].macroY * records[i].macroZ;
            for (uint64_t first = 0; first < cells; first += cellsPerDispatch) {
                const gpu::MajorantParams params{volumes, volumeData, i, static_cast<uint32_t>(first)};
                pipeline.pushConstants(cmd, &params, sizeof(params));
                const uint64_t count = std::min(cellsPerDispatch, cells - first);
                vkCmdDispatch(cmd, static_cast<uint32_t>((count + kWorkgroup - 1) / kWorkgroup), 1, 1);
            }
        }
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ripple::core
