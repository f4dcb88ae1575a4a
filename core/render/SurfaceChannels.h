// The frame channels read from the first visible hit (albedo, normal, primitiveId, objectId, instanceId):
// one buffer per channel asked for and none otherwise, cleared by pt_generate and filled by pt_channels
// (shaders/pt_channels.comp) from the SurfaceRecords of the camera rays.
#pragma once

#include "core/render/FeatureSet.h"
#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"

#include <cstdint>

namespace ripple::core {

enum class SurfaceChannel : uint32_t { Albedo = 0, Normal = 1, PrimitiveId = 2, ObjectId = 3, InstanceId = 4 };

class SurfaceChannels {
public:
    SurfaceChannels(const vk::Context& context, uint32_t workgroupSize);

    // Allocates the buffers of the channels asked for (and frees the others).
    void resize(uint64_t pixels, const FrameChannels& channels);
    bool any() const { return table_.handle() != VK_NULL_HANDLE; }
    bool has(SurfaceChannel channel) const;
    // The gpu::ChannelBuffers table for StageParams.results of pt_generate and pt_channels; 0 when no
    // channel was asked for.
    VkDeviceAddress tableAddress() const { return vk::addressOf(table_); }
    // The pipeline that fills the channels from `pathsAndSurfaces` (StageParams with paths and surfaces).
    const vk::ComputePipeline& pipeline();
    // Bytes allocated for these channels (0 when none was asked for).
    uint64_t bytes() const { return bytes_; }

    // Albedo and normal: three floats per pixel; the ids: one uint32 per pixel. Throws std::logic_error
    // for a channel that resize() was not asked for.
    void read(SurfaceChannel channel, void* destination) const;

private:
    const vk::Context& context_;
    uint32_t workgroupSize_;
    uint64_t pixels_ = 0;
    uint64_t bytes_ = 0;
    vk::Buffer buffers_[5];  // by SurfaceChannel
    vk::Buffer table_;
    vk::ComputePipeline pipeline_;  // built on first use
};

}  // namespace ripple::core
