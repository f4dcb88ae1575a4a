// What the viewer shows: the colour, or one of the frame's other channels turned into a picture (depth near
// bright and far dark, normals as 0.5 n + 0.5, albedo as it is, ids as distinct colours).
#pragma once

#include <anari/anari.h>

#include <array>
#include <cstdint>
#include <vector>

namespace ripple::apps {

enum class DisplayChannel : int { Color, Depth, Normal, Albedo, PrimitiveId, ObjectId, InstanceId };

struct DisplayChannelInfo {
    DisplayChannel channel;
    const char* label;                  // for the panel
    const char* parameter;              // the frame parameter that enables it ("channel.depth", ...)
    ANARIDataType type;                 // the element type it is mapped as
};

// Every channel the viewer can show, colour first.
const std::array<DisplayChannelInfo, 7>& displayChannels();
const DisplayChannelInfo& displayChannelInfo(DisplayChannel channel);

// Linear RGBA (rows as mapped) of `pixels` elements of a mapped channel: depth scaled between the nearest and
// farthest finite depth (no hit: black), normals 0.5 n + 0.5, albedo as it is, ids hashed to colours (~0u,
// none: black).
std::vector<float> channelPicture(DisplayChannel channel, const void* mapped, size_t pixels);

}  // namespace ripple::apps
