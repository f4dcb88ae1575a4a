// Dispatches volume_majorants.comp over each volume's coarse macrocells and chooses the grid
// (VolumeMajorants.h).
#include "core/scene/VolumeMajorants.h"

#include "core/scene/VolumeTable.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/volume_majorants.spv.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace ripple::core {

namespace {

uint64_t cellCount(glm::uvec3 cells) { return uint64_t(cells.x) * cells.y * cells.z; }

}  // namespace

MajorantGrids buildMajorantsOnDevice(const vk::Context& context, vk::Buffer& volumes, const vk::Buffer& volumeData,
                                     std::vector<gpu::VolumeRecord>& records) {
    MajorantGrids result;
    if (records.empty()) return result;
    for (const gpu::VolumeRecord& r : records)  // the kernel writes the coarse grid at majorantOffset
        if (r.macrocell != gpu::VOLUME_MACROCELL_COARSE)
            throw std::logic_error("buildMajorantsOnDevice: a volume record whose grid was already chosen");
    const auto start = std::chrono::steady_clock::now();
    constexpr uint32_t kWorkgroup = 64;  // volume_majorants.comp's local_size_x
    const vk::ComputePipeline pipeline(context, shaders::volume_majorants, "volume_majorants",
                                       static_cast<uint32_t>(sizeof(gpu::MajorantParams)));
    const uint64_t cellsPerDispatch = uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * kWorkgroup;
    const auto dimsOf = [](const gpu::VolumeRecord& r) { return glm::uvec3(r.dimX, r.dimY, r.dimZ); };
    // Per volume, the sum of the fine majorants under each coarse macrocell.
    std::vector<vk::Buffer> sums;
    for (const gpu::VolumeRecord& r : records)
        sums.emplace_back(context, cellCount(macrocellsPerAxis(dimsOf(r), gpu::VOLUME_MACROCELL_COARSE)) * sizeof(float),
                          "volume fine majorant sums");
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::computeBarrier(cmd);  // after the uploads
        pipeline.bind(cmd);
        for (uint32_t i = 0; i < records.size(); ++i) {
            const uint64_t cells = cellCount(macrocellsPerAxis(dimsOf(records[i]), gpu::VOLUME_MACROCELL_COARSE));
            for (uint64_t first = 0; first < cells; first += cellsPerDispatch) {
                const gpu::MajorantParams params{volumes.address(), volumeData.address(), sums[i].address(), i,
                                                 static_cast<uint32_t>(first)};
                pipeline.pushConstants(cmd, &params, sizeof(params));
                const uint64_t count = std::min(cellsPerDispatch, cells - first);
                vkCmdDispatch(cmd, static_cast<uint32_t>((count + kWorkgroup - 1) / kWorkgroup), 1, 1);
            }
        }
    });

    bool changed = false;
    for (size_t i = 0; i < records.size(); ++i) {
        gpu::VolumeRecord& r = records[i];
        const glm::uvec3 coarseCells = macrocellsPerAxis(dimsOf(r), gpu::VOLUME_MACROCELL_COARSE);
        const glm::uvec3 fineCells = macrocellsPerAxis(dimsOf(r), gpu::VOLUME_MACROCELL_FINE);
        std::vector<float> coarse(cellCount(coarseCells)), fineSums(coarse.size());
        volumeData.download(coarse.data(), coarse.size() * sizeof(float), VkDeviceSize(r.majorantOffset) * sizeof(float));
        sums[i].download(fineSums.data(), fineSums.size() * sizeof(float));
        // Each coarse majorant counted once for every fine macrocell under it.
        constexpr uint32_t ratio = gpu::VOLUME_MACROCELL_COARSE / gpu::VOLUME_MACROCELL_FINE;
        double coarseTotal = 0.0, fineTotal = 0.0;
        for (uint32_t z = 0; z < coarseCells.z; ++z)
            for (uint32_t y = 0; y < coarseCells.y; ++y)
                for (uint32_t x = 0; x < coarseCells.x; ++x) {
                    const glm::uvec3 from = glm::uvec3(x, y, z) * ratio;
                    const glm::uvec3 under = glm::min(from + ratio, fineCells) - from;
                    const size_t cell = (size_t(z) * coarseCells.y + y) * coarseCells.x + x;
                    coarseTotal += double(coarse[cell]) * cellCount(under);
                    fineTotal += double(fineSums[cell]);
                }
        if (coarseTotal > 0.0 && fineTotal * kFineGridGain <= coarseTotal) {
            r.macrocell = gpu::VOLUME_MACROCELL_FINE;
            r.macroX = fineCells.x;
            r.macroY = fineCells.y;
            r.macroZ = fineCells.z;
            r.majorantOffset = r.fineOffset;
            ++result.fineVolumes;
            changed = true;
        }
    }
    if (changed) volumes.upload(records.data(), records.size() * sizeof(gpu::VolumeRecord));
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace ripple::core
