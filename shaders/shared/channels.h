// The optional frame channels besides color and depth: one buffer per channel asked for, none otherwise.
// pt_generate clears them for each camera ray and pt_channels fills them from the first visible hit.
#ifndef RIPPLE_SHARED_CHANNELS_H
#define RIPPLE_SHARED_CHANNELS_H
#include "common.h"

RIPPLE_GPU_BEGIN

// Device addresses, 0 where the channel was not asked for. Values are those of the latest sample.
struct ChannelBuffers {
    uint64_t albedo;       // vec4 per pixel: rgb base color at the first hit (0 where nothing was hit)
    uint64_t normal;       // vec4 per pixel: xyz world-space shading normal, facing the camera (0 on a miss)
    uint64_t primitiveId;  // uint per pixel, ~0u on a miss
    uint64_t objectId;     // uint per pixel, ~0u on a miss
    uint64_t instanceId;   // uint per pixel, ~0u on a miss
    uint64_t pad0;
};

RIPPLE_GPU_END
#endif
