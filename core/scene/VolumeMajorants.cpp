// Dispatches volume_majorants.comp over each volume's macrocells and sets cellByCell (VolumeMajorants.h).
#include "core/scene/VolumeMajorants.h"

#include "core/scene/VolumeTable.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/volume_majorants.spv.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <chrono>

namespace ripple::core {

namespace {

uint64_t cellCount(glm::uvec3 cells) { return uint64_t(cells.x) * cells.y * cells.z; }

glm::uvec3 dimsOf(const gpu::VolumeRecord& r) { return glm::uvec3(r.dimX, r.dimY, r.dimZ); }

// The longest edge of one of the volume's cells in world units: the longest column of the linear part of
// its grid-to-world map. A ray's crossing of one cell, 1 / (|dx| + |dy| + |dz|) in grid units, is at most
// that long in the world.
float longestCellEdge(const gpu::VolumeRecord& record) {
    glm::mat3 worldToGrid;  // linear part; the record holds its rows
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) worldToGrid[column][row] = record.worldToGrid[row][column];
    const glm::mat3 gridToWorld = glm::inverse(worldToGrid);
    return std::max({glm::length(gridToWorld[0]), glm::length(gridToWorld[1]), glm::length(gridToWorld[2])});
}

}  // namespace

MajorantGrids buildMajorantsOnDevice(const vk::Context& context, vk::Buffer& volumes, const vk::Buffer& volumeData,
                                     std::vector<gpu::VolumeRecord>& records) {
    MajorantGrids result;
    if (records.empty()) return result;
    const auto start = std::chrono::steady_clock::now();
    constexpr uint32_t kWorkgroup = 64;  // volume_majorants.comp's local_size_x
    const vk::ComputePipeline pipeline(context, shaders::volume_majorants, "volume_majorants",
                                       static_cast<uint32_t>(sizeof(gpu::MajorantParams)));
    const uint64_t cellsPerDispatch = uint64_t(context.properties().limits.maxComputeWorkGroupCount[0]) * kWorkgroup;
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::computeBarrier(cmd);  // after the uploads
        pipeline.bind(cmd);
        for (uint32_t i = 0; i < records.size(); ++i) {
            if (records[i].kind != gpu::VOLUME_KIND_STRUCTURED) continue;  // its majorants came with its table
            const uint64_t cells = cellCount(macrocellsPerAxis(dimsOf(records[i])));
            for (uint64_t first = 0; first < cells; first += cellsPerDispatch) {
                const gpu::MajorantParams params{volumes.address(), volumeData.address(), i, static_cast<uint32_t>(first)};
                pipeline.pushConstants(cmd, &params, sizeof(params));
                const uint64_t count = std::min(cellsPerDispatch, cells - first);
                pipeline.dispatch(cmd, (count + kWorkgroup - 1) / kWorkgroup);
            }
        }
    });

    bool changed = false;
    for (gpu::VolumeRecord& r : records) {
        const bool refinable = r.kind == gpu::VOLUME_KIND_STRUCTURED && r.filterMode == gpu::VOLUME_FILTER_LINEAR && r.dimX > 1 && r.dimY > 1 && r.dimZ > 1;
        if (!refinable) continue;
        std::vector<float> majorants(cellCount(macrocellsPerAxis(dimsOf(r))));
        volumeData.download(majorants.data(), majorants.size() * sizeof(float), VkDeviceSize(r.majorantOffset) * sizeof(float));
        const float largest = *std::max_element(majorants.begin(), majorants.end());
        if (largest * longestCellEdge(r) >= gpu::VOLUME_REFINE_DEPTH) {
            r.cellByCell = 1;
            ++result.cellByCellVolumes;
            changed = true;
        }
    }
    if (changed) volumes.upload(records.data(), records.size() * sizeof(gpu::VolumeRecord));
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace ripple::core
