// Pictures of the frame channels (see ChannelView.h).
#include "apps/ripple-view/ChannelView.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ripple::apps {

const std::array<DisplayChannelInfo, 7>& displayChannels() {
    static const std::array<DisplayChannelInfo, 7> channels = {{
        {DisplayChannel::Color, "colour", "channel.color", ANARI_FLOAT32_VEC4},
        {DisplayChannel::Depth, "depth", "channel.depth", ANARI_FLOAT32},
        {DisplayChannel::Normal, "normal", "channel.normal", ANARI_FLOAT32_VEC3},
        {DisplayChannel::Albedo, "albedo", "channel.albedo", ANARI_FLOAT32_VEC3},
        {DisplayChannel::PrimitiveId, "primitive id", "channel.primitiveId", ANARI_UINT32},
        {DisplayChannel::ObjectId, "object id", "channel.objectId", ANARI_UINT32},
        {DisplayChannel::InstanceId, "instance id", "channel.instanceId", ANARI_UINT32},
    }};
    return channels;
}

const DisplayChannelInfo& displayChannelInfo(DisplayChannel channel) {
    return displayChannels()[size_t(channel)];
}

std::vector<float> channelPicture(DisplayChannel channel, const void* mapped, size_t pixels) {
    std::vector<float> rgba(pixels * 4, 1.0f);
    const auto set = [&](size_t i, float r, float g, float b) {
        rgba[i * 4] = r;
        rgba[i * 4 + 1] = g;
        rgba[i * 4 + 2] = b;
    };
    switch (channel) {
    case DisplayChannel::Color: {
        const auto* c = static_cast<const float*>(mapped);
        std::copy(c, c + pixels * 4, rgba.begin());
        break;
    }
    case DisplayChannel::Depth: {
        const auto* d = static_cast<const float*>(mapped);
        float nearest = std::numeric_limits<float>::infinity(), farthest = -nearest;
        for (size_t i = 0; i < pixels; ++i)
            if (std::isfinite(d[i])) nearest = std::min(nearest, d[i]), farthest = std::max(farthest, d[i]);
        const float range = farthest > nearest ? farthest - nearest : 1.0f;
        for (size_t i = 0; i < pixels; ++i) {
            const float v = std::isfinite(d[i]) ? 1.0f - 0.9f * (d[i] - nearest) / range : 0.0f;
            set(i, v, v, v);
        }
        break;
    }
    case DisplayChannel::Normal: {
        const auto* n = static_cast<const float*>(mapped);
        for (size_t i = 0; i < pixels; ++i)
            set(i, 0.5f * n[i * 3] + 0.5f, 0.5f * n[i * 3 + 1] + 0.5f, 0.5f * n[i * 3 + 2] + 0.5f);
        break;
    }
    case DisplayChannel::Albedo: {
        const auto* a = static_cast<const float*>(mapped);
        for (size_t i = 0; i < pixels; ++i) set(i, a[i * 3], a[i * 3 + 1], a[i * 3 + 2]);
        break;
    }
    case DisplayChannel::PrimitiveId:
    case DisplayChannel::ObjectId:
    case DisplayChannel::InstanceId: {
        const auto* id = static_cast<const uint32_t*>(mapped);
        for (size_t i = 0; i < pixels; ++i) {
            if (id[i] == ~0u) {
                set(i, 0.0f, 0.0f, 0.0f);
                continue;
            }
            // A 32-bit integer hash (Wang's), three bytes of it as a colour kept off black.
            uint32_t h = id[i];
            h = (h ^ 61u) ^ (h >> 16);
            h *= 9u;
            h ^= h >> 4;
            h *= 0x27d4eb2du;
            h ^= h >> 15;
            set(i, 0.2f + 0.8f * float(h & 255u) / 255.0f, 0.2f + 0.8f * float((h >> 8) & 255u) / 255.0f,
                0.2f + 0.8f * float((h >> 16) & 255u) / 255.0f);
        }
        break;
    }
    }
    return rgba;
}

}  // namespace ripple::apps
