// Frame memory estimate and the memory available to it (see FrameMemory.h). The estimate follows the
// buffers PathTracer::resize and readColor allocate, and the copies Frame keeps for anariMapFrame.
#include "anari/device/frame/FrameMemory.h"

#include "core/render/PathTracer.h"
#include "core/vk/Context.h"
#include "shaders/shared/path.h"
#include "shaders/shared/ray.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

namespace ripple::device {
namespace {

// a * b + c, or nullopt past 2^64.
std::optional<uint64_t> mulAdd(uint64_t a, uint64_t b, uint64_t c = 0) {
    uint64_t product = 0, sum = 0;
    if (__builtin_mul_overflow(a, b, &product) || __builtin_add_overflow(product, c, &sum)) return std::nullopt;
    return sum;
}

std::string gib(uint64_t bytes) {
    char text[32];
    if (bytes < (1ull << 30)) std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1ull << 20));
    else std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
    return text;
}

// MemAvailable of /proc/meminfo (what can be allocated without swapping), else the free pages.
uint64_t hostAvailable() {
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        uint64_t kib = 0;
        if (key == "MemAvailable:" && meminfo >> kib) return kib * 1024;
        meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    const long pages = sysconf(_SC_AVPHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : std::numeric_limits<uint64_t>::max();
}

}  // namespace

std::optional<FrameMemory> estimateFrameMemory(glm::uvec2 size, ANARIDataType colorType,
                                               const core::FrameChannels& channels) {
    const uint64_t pixels = uint64_t(size.x) * uint64_t(size.y);  // two 32-bit factors: cannot overflow
    // Per pixel on the device: the accumulation (vec4), the sample count, the resolved color (always
    // vec4, whatever format is read back), depth, and the surface channels (albedo and normal as vec4,
    // ids as uint32).
    uint64_t devicePerPixel = 16 + 4 + 16;
    if (channels.depth) devicePerPixel += 4;
    if (channels.albedo) devicePerPixel += 16;
    if (channels.normal) devicePerPixel += 16;
    devicePerPixel += 4 * (uint64_t(channels.primitiveId) + channels.objectId + channels.instanceId);
    // Paths in flight are capped (PathTracerOptions::queueCapacity), and a frame of fewer pixels than
    // packedWavePaths may trace up to that many: two path queues, hits, surface records, shadow rays and
    // requests, occlusion flags. The sample radiance (vec4) of a pass's slots: one per pixel, or for several
    // samples of each pixel up to queueCapacity (PathTracer's samplesPerPass).
    const core::PathTracerOptions tracer;
    const uint64_t capacity = std::min<uint64_t>(std::max<uint64_t>(pixels, tracer.packedWavePaths), tracer.queueCapacity);
    const uint64_t perPath = 2 * (sizeof(gpu::PathState) + sizeof(gpu::Ray)) + sizeof(gpu::Hit) +
                             sizeof(gpu::SurfaceRecord) + sizeof(gpu::Ray) + sizeof(gpu::ShadowRequest) + 4;
    // On the host: the mapped copies, plus one readback staged through host memory at a time (vec4).
    uint64_t hostPerPixel = colorType == ANARI_FLOAT32_VEC4 ? 16 : colorType != ANARI_UNKNOWN ? 4 : 0;
    if (channels.depth) hostPerPixel += 4;
    if (channels.albedo) hostPerPixel += 12;
    if (channels.normal) hostPerPixel += 12;
    hostPerPixel += 4 * (uint64_t(channels.primitiveId) + channels.objectId + channels.instanceId);
    hostPerPixel += 16;

    const std::optional<uint64_t> sampleRadiance = mulAdd(std::max<uint64_t>(pixels, tracer.queueCapacity), 16);
    const std::optional<uint64_t> queues = sampleRadiance ? mulAdd(capacity, perPath, *sampleRadiance) : std::nullopt;
    if (!queues) return std::nullopt;
    const std::optional<uint64_t> device = mulAdd(pixels, devicePerPixel, *queues);
    const std::optional<uint64_t> host = mulAdd(pixels, hostPerPixel);
    if (!device || !host || *device > std::numeric_limits<uint64_t>::max() - *host) return std::nullopt;
    return FrameMemory{*device, *host};
}

AvailableMemory availableMemory(const vk::Context& context) {
    AvailableMemory available;
    available.hostBytes = hostAvailable();
    const VkPhysicalDeviceType type = context.properties().deviceType;
    available.unified = type == VK_PHYSICAL_DEVICE_TYPE_CPU || type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties();
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            available.deviceBytes = std::max<uint64_t>(available.deviceBytes, memory.memoryHeaps[h].size);
    if (const char* limit = std::getenv("RIPPLE_MEMORY_LIMIT"); limit && *limit) {
        char* end = nullptr;
        const unsigned long long bytes = std::strtoull(limit, &end, 10);
        if (end && *end == '\0') {
            available.hostBytes = std::min<uint64_t>(available.hostBytes, bytes);
            available.deviceBytes = std::min<uint64_t>(available.deviceBytes, bytes);
        }
    }
    return available;
}

std::string whyFrameDoesNotFit(glm::uvec2 size, const std::optional<FrameMemory>& needed, const AvailableMemory& available) {
    const std::string frame = "a " + std::to_string(size.x) + "x" + std::to_string(size.y) + " frame with its channels";
    if (!needed) return frame + " needs more than 2^64 bytes";
    const std::string need = frame + " needs " + std::to_string(needed->total()) + " bytes (" + gib(needed->total()) +
                             ": " + gib(needed->deviceBytes) + " on the device, " + gib(needed->hostBytes) + " on the host)";
    if (available.unified) {
        if (needed->total() <= available.hostBytes) return {};
        return need + " but only " + std::to_string(available.hostBytes) + " bytes (" + gib(available.hostBytes) +
               ") are available; use a smaller size or fewer channels";
    }
    if (needed->deviceBytes > available.deviceBytes)
        return need + " but the device has " + std::to_string(available.deviceBytes) + " bytes (" +
               gib(available.deviceBytes) + "); use a smaller size or fewer channels";
    if (needed->hostBytes > available.hostBytes)
        return need + " but only " + std::to_string(available.hostBytes) + " bytes (" + gib(available.hostBytes) +
               ") of host memory are available; use a smaller size or fewer channels";
    return {};
}

}  // namespace ripple::device
