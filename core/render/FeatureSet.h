// Leave out what a scene does not need: the FeatureSet of a frame (geometry kinds, textures, emission,
// alpha, light kinds, channels, ranks) and the cache of compute pipelines specialised for it. Kernels read
// the mask as specialization constant 1 (shaders/features.glsl), so the code of an absent feature is
// removed when the pipeline is built: a triangle-only scene traces with a kernel that has no sphere,
// cylinder or cone test at all.
#pragma once

#include "core/scene/SceneDescription.h"
#include "core/vk/ComputePipeline.h"
#include "shaders/shared/features.h"

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace ripple::core {

struct FeatureSet {
    uint32_t bits = 0;  // gpu::FEATURE_*

    bool has(uint32_t feature) const { return (bits & feature) != 0; }
    static FeatureSet all() { return {gpu::FEATURE_ALL}; }
    // "triangles textures lights:point depth": for logs and test messages.
    std::string describe() const;
};

// The material and light part of a scene's features: FEATURE_TEXTURES when a material used by an instance
// reads a texture, FEATURE_EMISSIVE when one emits, FEATURE_ALPHA when one has opacity below 1,
// FEATURE_PHYSICALLY_BASED (and FEATURE_CLEARCOAT, FEATURE_TRANSMISSION) when one is physicallyBased (with a
// clear coat, with transmission), and one FEATURE_LIGHT_SHIFT + kind bit per light kind present. (The
// geometry bits come from the instances that core::Scene keeps, and the bit of emissive triangles from its
// light records; see Scene::features.)
uint32_t shadingFeatures(const SceneDescription& description);

// The frame channels besides color, each of which gets a buffer only when asked for.
struct FrameChannels {
    bool depth = false;
    bool albedo = false;       // FLOAT32_VEC3: base color at the first visible hit
    bool normal = false;       // FLOAT32_VEC3: world-space shading normal at the first visible hit
    bool primitiveId = false;  // UINT32: the application's primitive index (quads count once)
    bool objectId = false;     // UINT32: the surface's "id"
    bool instanceId = false;   // UINT32: the instance's "id"
};
uint32_t channelFeatures(const FrameChannels& channels);

// One compute kernel as the cache builds it: its SPIR-V, and the feature bits it is specialised on (the
// others are cleared from its key, so e.g. asking for a depth channel does not rebuild the traversal).
struct KernelSource {
    std::span<const uint32_t> spirv;
    std::string name;
    uint32_t pushConstantBytes = 0;
    uint32_t workgroupSize = 64;
    uint32_t relevantFeatures = gpu::FEATURE_ALL;
};

// A tracer's pipelines per (kernel, relevant features): which variant sits in each of its slots, and the
// others it has used. The kernel in use sits in the owner's own vk::ComputePipeline member (its "slot"), so
// code that holds a reference to that member always dispatches the selected variant; select() swaps
// variants in and out of the slot. The device builds each variant once and owns it
// (vk::Context::storedPipeline), so a second tracer's select() builds nothing either.
class PipelineCache {
public:
    explicit PipelineCache(const vk::Context& context) : context_(&context) {}

    // A pipeline of `kernel` specialised for `features` (only its relevant bits).
    static vk::ComputePipeline build(const vk::Context& context, const KernelSource& kernel, uint32_t features);

    // Puts the variant of `kernel` for `features` into `slot`, keeping the one that was there (built by
    // build() or select() for the same kernel; FEATURE_ALL when `slot` was never selected before).
    void select(const KernelSource& kernel, uint32_t features, vk::ComputePipeline& slot);

    struct Entry {
        std::string kernel;
        uint32_t features;  // the specialised bits (already masked by the kernel's relevant features)
        bool inUse;         // sitting in a slot now
    };
    std::vector<Entry> entries() const;

private:
    struct SlotState {
        std::string kernel;
        uint32_t features;
    };
    const vk::Context* context_;
    std::map<std::pair<std::string, uint32_t>, vk::ComputePipeline> stored_;  // variants not in a slot
    std::map<const vk::ComputePipeline*, SlotState> slots_;
};

}  // namespace ripple::core
