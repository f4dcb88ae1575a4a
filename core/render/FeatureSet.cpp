// FeatureSet derivation and the cache of specialised pipelines (see FeatureSet.h).
#include "core/render/FeatureSet.h"

#include <utility>

namespace ripple::core {

namespace {

constexpr uint32_t kWorkgroupSizeConstant = 0;  // layout(local_size_x_id = 0) in every kernel
constexpr uint32_t kFeaturesConstant = 1;       // layout(constant_id = 1) in shaders/features.glsl

}  // namespace

std::string FeatureSet::describe() const {
    static const std::pair<uint32_t, const char*> names[] = {
        {gpu::FEATURE_TRIANGLES, "triangles"},      {gpu::FEATURE_SPHERES, "spheres"},
        {gpu::FEATURE_CYLINDERS, "cylinders"},      {gpu::FEATURE_CONES, "cones"},
        {gpu::FEATURE_VOLUMES, "volumes"},          {gpu::FEATURE_TEXTURES, "textures"},
        {gpu::FEATURE_EMISSIVE, "emissive"},        {gpu::FEATURE_ALPHA, "alpha"},
        {gpu::FEATURE_CHANNEL_DEPTH, "depth"},      {gpu::FEATURE_CHANNEL_ALBEDO, "albedo"},
        {gpu::FEATURE_CHANNEL_NORMAL, "normal"},    {gpu::FEATURE_CHANNEL_PRIMITIVE_ID, "primitiveId"},
        {gpu::FEATURE_CHANNEL_OBJECT_ID, "objectId"}, {gpu::FEATURE_CHANNEL_INSTANCE_ID, "instanceId"},
        {gpu::FEATURE_MULTI_RANK, "ranks"},        {gpu::FEATURE_ISOSURFACES, "isosurfaces"},
        {gpu::FEATURE_MESH_ISOSURFACES, "meshIsosurfaces"},
        {gpu::FEATURE_UNSTRUCTURED_VOLUMES, "unstructuredVolumes"}, {gpu::FEATURE_NANOVDB_VOLUMES, "nanovdbVolumes"},
        {gpu::FEATURE_AMR_VOLUMES, "amrVolumes"},
        {gpu::FEATURE_PHYSICALLY_BASED, "physicallyBased"}, {gpu::FEATURE_CLEARCOAT, "clearcoat"},
        {gpu::FEATURE_TRANSMISSION, "transmission"}};
    std::string text;
    auto add = [&](const std::string& word) { text += (text.empty() ? "" : " ") + word; };
    for (const auto& [bit, name] : names)
        if (has(bit)) add(name);
    for (uint32_t kind = 0; kind < 8; ++kind)
        if (has(1u << (gpu::FEATURE_LIGHT_SHIFT + kind))) add("light:" + std::to_string(kind));
    return text.empty() ? "none" : text;
}

uint32_t shadingFeatures(const SceneDescription& description) {
    uint32_t bits = 0;
    std::vector<bool> used(description.materials.size(), false);
    for (const InstanceDescription& instance : description.instances)
        if (instance.materialIndex < used.size()) used[instance.materialIndex] = true;
    for (size_t m = 0; m < description.materials.size(); ++m) {
        if (!used[m]) continue;
        const Material& material = description.materials[m];
        for (int32_t texture : {material.baseColorTexture, material.normalTexture, material.metallicTexture,
                                material.roughnessTexture, material.emissiveTexture, material.opacityTexture})
            if (texture != kNoTexture) bits |= gpu::FEATURE_TEXTURES;
        if (glm::any(glm::greaterThan(material.emissive, glm::vec3(0.0f)))) bits |= gpu::FEATURE_EMISSIVE;
        if (material.opacity < 1.0f) bits |= gpu::FEATURE_ALPHA;
        if (material.kind == Material::Kind::PhysicallyBased) {
            bits |= gpu::FEATURE_PHYSICALLY_BASED;
            if (material.clearcoat > 0.0f) bits |= gpu::FEATURE_CLEARCOAT;
            if (material.transmission > 0.0f) bits |= gpu::FEATURE_TRANSMISSION;
        }
    }
    for (const Light& light : description.lights) {
        const uint32_t kind = static_cast<uint32_t>(light.kind);
        bits |= kind < 8 ? 1u << (gpu::FEATURE_LIGHT_SHIFT + kind) : gpu::FEATURE_LIGHTS;
    }
    return bits;
}

uint32_t channelFeatures(const FrameChannels& channels) {
    return (channels.depth ? gpu::FEATURE_CHANNEL_DEPTH : 0u) | (channels.albedo ? gpu::FEATURE_CHANNEL_ALBEDO : 0u) |
           (channels.normal ? gpu::FEATURE_CHANNEL_NORMAL : 0u) |
           (channels.primitiveId ? gpu::FEATURE_CHANNEL_PRIMITIVE_ID : 0u) |
           (channels.objectId ? gpu::FEATURE_CHANNEL_OBJECT_ID : 0u) |
           (channels.instanceId ? gpu::FEATURE_CHANNEL_INSTANCE_ID : 0u);
}

vk::ComputePipeline PipelineCache::build(const vk::Context& context, const KernelSource& kernel, uint32_t features) {
    const vk::SpecializationConstant constants[] = {{kWorkgroupSizeConstant, kernel.workgroupSize},
                                                    {kFeaturesConstant, features & kernel.relevantFeatures}};
    return vk::ComputePipeline(context, kernel.spirv, kernel.name, kernel.pushConstantBytes, constants);
}

void PipelineCache::select(const KernelSource& kernel, uint32_t features, vk::ComputePipeline& slot) {
    const uint32_t key = features & kernel.relevantFeatures;
    SlotState& state = slots_.try_emplace(&slot, SlotState{kernel.name, gpu::FEATURE_ALL & kernel.relevantFeatures}).first->second;
    if (slot.handle() != VK_NULL_HANDLE && state.kernel == kernel.name && state.features == key) return;
    if (slot.handle() != VK_NULL_HANDLE) stored_.insert_or_assign({state.kernel, state.features}, std::move(slot));
    if (auto found = stored_.find({kernel.name, key}); found != stored_.end()) {
        slot = std::move(found->second);
        stored_.erase(found);
    } else {
        slot = build(*context_, kernel, key);
    }
    state = SlotState{kernel.name, key};
}

std::vector<PipelineCache::Entry> PipelineCache::entries() const {
    std::vector<Entry> list;
    for (const auto& [key, pipeline] : stored_) list.push_back({key.first, key.second, false});
    for (const auto& [slot, state] : slots_)
        if (slot->handle() != VK_NULL_HANDLE) list.push_back({state.kernel, state.features, true});
    return list;
}

}  // namespace ripple::core
