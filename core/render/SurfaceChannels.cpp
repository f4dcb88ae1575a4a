// Buffers and readback of the surface channels (see SurfaceChannels.h).
#include "core/render/SurfaceChannels.h"

#include "shaders/pt_channels.spv.h"
#include "shaders/shared/channels.h"
#include "shaders/shared/path.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::core {

namespace {

const char* const kNames[] = {"albedo", "normal", "primitiveId", "objectId", "instanceId"};

bool isVector(SurfaceChannel channel) { return channel == SurfaceChannel::Albedo || channel == SurfaceChannel::Normal; }

}  // namespace

SurfaceChannels::SurfaceChannels(const vk::Context& context, uint32_t workgroupSize)
    : context_(context), workgroupSize_(workgroupSize) {}

void SurfaceChannels::resize(uint64_t pixels, const FrameChannels& channels) {
    const bool wanted[] = {channels.albedo, channels.normal, channels.primitiveId, channels.objectId, channels.instanceId};
    pixels_ = pixels;
    bytes_ = 0;
    gpu::ChannelBuffers table{};
    uint64_t* addresses[] = {&table.albedo, &table.normal, &table.primitiveId, &table.objectId, &table.instanceId};
    bool anyWanted = false;
    for (uint32_t c = 0; c < 5; ++c) {
        buffers_[c] = vk::Buffer();
        if (!wanted[c]) continue;
        const uint64_t bytes = pixels * (isVector(SurfaceChannel(c)) ? sizeof(gpu::vec4) : sizeof(uint32_t));
        buffers_[c] = vk::Buffer(context_, bytes, std::string("frame ") + kNames[c]);
        *addresses[c] = buffers_[c].address();
        bytes_ += bytes;
        anyWanted = true;
    }
    table_ = vk::Buffer();
    if (!anyWanted) return;
    table_ = vk::Buffer(context_, sizeof(table), "frame channel table");
    table_.upload(&table, sizeof(table));
    bytes_ += sizeof(table);
}

bool SurfaceChannels::has(SurfaceChannel channel) const {
    const auto c = static_cast<uint32_t>(channel);
    return c < 5 && buffers_[c].handle() != VK_NULL_HANDLE;
}

const vk::ComputePipeline& SurfaceChannels::pipeline() {
    if (pipeline_.handle() == VK_NULL_HANDLE)
        pipeline_ = PipelineCache::build(context_, {shaders::pt_channels, "pt_channels",
                                                    static_cast<uint32_t>(sizeof(gpu::StageParams)), workgroupSize_, 0},
                                         0);
    return pipeline_;
}

void SurfaceChannels::read(SurfaceChannel channel, void* destination) const {
    if (!has(channel))
        throw std::logic_error(std::string("PathTracer: the ") +
                               (static_cast<uint32_t>(channel) < 5 ? kNames[static_cast<uint32_t>(channel)] : "unknown") +
                               " channel was not asked for in resize()");
    const vk::Buffer& buffer = buffers_[static_cast<uint32_t>(channel)];
    if (!isVector(channel)) {
        buffer.download(destination, pixels_ * sizeof(uint32_t));
        return;
    }
    std::vector<gpu::vec4> values(pixels_);
    buffer.download(values.data(), pixels_ * sizeof(gpu::vec4));
    auto* out = static_cast<float*>(destination);
    for (uint64_t i = 0; i < pixels_; ++i)
        for (int k = 0; k < 3; ++k) out[3 * i + k] = values[i][k];
}

}  // namespace ripple::core
