// What a frame of a given size and channels costs in memory, and what the machine has to give: a frame
// that does not fit is refused before anything is allocated, never left to exhaust the machine.
#pragma once

#include "anari/anari.h"
#include "core/render/FeatureSet.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace ripple::vk {
class Context;
}

namespace ripple::device {

struct FrameMemory {
    uint64_t deviceBytes = 0;  // the path tracer's buffers: accumulation, sample radiance and counts, channels, queues
    uint64_t hostBytes = 0;    // the frame's copies of its channels for anariMapFrame, and one readback in flight
    uint64_t total() const { return deviceBytes + hostBytes; }
};

// Every size in 64 bits with overflow checks: nullopt when a count does not fit (no frame that large can
// be rendered anyway).
std::optional<FrameMemory> estimateFrameMemory(glm::uvec2 size, ANARIDataType colorType,
                                               const core::FrameChannels& channels);

// Memory the frame may still take: the system's MemAvailable (host), and for a GPU with its own memory,
// its largest device-local heap. RIPPLE_MEMORY_LIMIT (bytes) caps both, for a machine that is shared.
struct AvailableMemory {
    uint64_t hostBytes = 0;
    uint64_t deviceBytes = 0;
    bool unified = true;       // device memory is host memory (lavapipe, integrated GPUs): one pool
};
AvailableMemory availableMemory(const vk::Context& context);

// Empty when `needed` fits in `available`; otherwise why not, naming the frame size, the bytes needed and
// the bytes available.
std::string whyFrameDoesNotFit(glm::uvec2 size, const std::optional<FrameMemory>& needed, const AvailableMemory& available);

}  // namespace ripple::device
