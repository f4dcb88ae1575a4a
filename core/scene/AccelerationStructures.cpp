// Building the ray-query back-end's acceleration structures: sizes, storage and scratch on the host, then
// every BLAS in one vkCmdBuildAccelerationStructuresKHR call and the TLAS after a barrier.
#include "core/scene/AccelerationStructures.h"

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::core {

struct AccelerationStructures::Structure {
    const vk::Context* context = nullptr;
    vk::Buffer storage;
    VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
    VkDeviceAddress address = 0;

    Structure(const vk::Context& c, VkAccelerationStructureTypeKHR type, VkDeviceSize bytes, const std::string& name)
        : context(&c),
          storage(c, bytes, name + " storage", VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR) {
        const auto& fn = c.accelerationStructureFunctions();
        VkAccelerationStructureCreateInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
        info.buffer = storage.handle();
        info.size = bytes;
        info.type = type;
        RIPPLE_VK_CHECK(fn.create(c.device(), &info, nullptr, &handle));
        c.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, reinterpret_cast<uint64_t>(handle), name);
        VkAccelerationStructureDeviceAddressInfoKHR addressInfo{
            VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
        addressInfo.accelerationStructure = handle;
        address = fn.deviceAddress(c.device(), &addressInfo);
    }
    ~Structure() {
        if (handle) context->accelerationStructureFunctions().destroy(context->device(), handle, nullptr);
    }
    Structure(const Structure&) = delete;
    Structure& operator=(const Structure&) = delete;
};

namespace {

constexpr VkBufferUsageFlags kBuildInput = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) { return (value + alignment - 1) / alignment * alignment; }

VkAabbPositionsKHR toAabb(const bvh::Aabb& box) {
    return {box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z};
}

// Boxes of one geometry's primitives in leaf order, never smaller than what intersect.glsl can hit.
void appendBoxes(const AccelerationGeometry& g, const AccelerationInputs& in, std::vector<VkAabbPositionsKHR>& out) {
    for (uint32_t i = g.primOffset; i < g.primOffset + g.primCount; ++i) {
        switch (g.kind) {
        case GeometryKind::Spheres: {
            const glm::vec3 c = in.spheres[i].centerRadius;
            const float r = in.spheres[i].centerRadius.w;
            const glm::vec3 pad = 1e-6f * (glm::abs(c) + glm::vec3(r));
            out.push_back(toAabb({c - glm::vec3(r) - pad, c + glm::vec3(r) + pad}));
            break;
        }
        case GeometryKind::Cylinders: {
            const gpu::CylinderPrim& p = in.cylinders[i];
            out.push_back(toAabb(coneBox(glm::vec3(p.p0Radius), p.p0Radius.w, glm::vec3(p.p1), p.p0Radius.w, false)));
            break;
        }
        case GeometryKind::Cones: {
            const gpu::ConePrim& p = in.cones[i];
            out.push_back(toAabb(coneBox(glm::vec3(p.p0Radius), p.p0Radius.w, glm::vec3(p.p1Radius), p.p1Radius.w,
                                         (p.flags & gpu::CONE_ROUND) != 0)));
            break;
        }
        case GeometryKind::Isosurfaces: {
            const gpu::IsoCellPrim& p = in.isoCells[i];
            const glm::vec3 lo(p.lowCorner), size(p.size);
            const glm::vec3 pad = 1e-6f * (glm::abs(lo) + size);
            out.push_back(toAabb({lo - pad, lo + size + pad}));
            break;
        }
        case GeometryKind::Triangles: break;
        }
    }
}

}  // namespace

AccelerationStructures::AccelerationStructures(const vk::Context& context, const AccelerationInputs& in,
                                               const AccelerationStructures* previous)
    : context_(context) {
    const auto start = std::chrono::steady_clock::now();
    if (!context.supportsRayQuery())
        throw std::runtime_error("acceleration structures need ray queries, which Vulkan device " + context.deviceName() +
                                 " lacks: " + context.rayQueryMissing());
    if (in.instances.size() >= (1u << 24))
        throw std::runtime_error("ray-query traversal supports at most 2^24 - 1 instances (a TLAS custom index has 24 "
                                 "bits), not " + std::to_string(in.instances.size()));
    const auto& fn = context.accelerationStructureFunctions();
    const VkDevice device = context.device();
    const VkDeviceSize scratchAlignment = context.accelerationStructureScratchAlignment();

    // 1. Reuse, or describe a BLAS build. The AABB inputs of all procedural geometries share one buffer.
    const size_t count = in.geometries.size();
    keys_.resize(count);
    blas_.resize(count);
    std::vector<size_t> toBuild;
    std::vector<VkDeviceSize> boxOffset(count, 0);
    std::vector<VkAabbPositionsKHR> boxes;
    for (size_t g = 0; g < count; ++g) {
        const AccelerationGeometry& geometry = in.geometries[g];
        if (geometry.primCount == 0) continue;
        keys_[g] = geometry.prepared;
        if (previous)
            for (size_t p = 0; p < previous->keys_.size() && !blas_[g]; ++p)
                if (previous->keys_[p] && previous->keys_[p] == geometry.prepared) blas_[g] = previous->blas_[p];
        if (blas_[g]) {
            ++blasReused_;
            continue;
        }
        toBuild.push_back(g);
        primitivesBuilt_ += geometry.primCount;
        if (geometry.kind != GeometryKind::Triangles) {
            boxOffset[g] = boxes.size() * sizeof(VkAabbPositionsKHR);
            appendBoxes(geometry, in, boxes);
        }
    }
    blasBuilt_ = toBuild.size();
    vk::Buffer boxBuffer;
    if (!boxes.empty()) {
        boxBuffer = vk::Buffer(context, boxes.size() * sizeof(VkAabbPositionsKHR), "BLAS input boxes", kBuildInput);
        boxBuffer.upload(boxes.data(), boxBuffer.size());
    }

    // One build per BLAS, then the TLAS last. Each build info points at its item's geometry.
    struct Build {
        VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
        VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
        VkAccelerationStructureBuildRangeInfoKHR range{};
        VkDeviceSize scratchOffset = 0;
    };
    std::vector<Build> builds;
    builds.resize(toBuild.size() + 1);
    VkDeviceSize scratchBytes = 0;
    auto sizeAndCreate = [&](VkAccelerationStructureBuildGeometryInfoKHR& info, uint32_t primitives, size_t item,
                             const std::string& name) {
        VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
        fn.buildSizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &primitives, &sizes);
        auto structure = std::make_unique<Structure>(context, info.type, sizes.accelerationStructureSize, name);
        info.dstAccelerationStructure = structure->handle;
        builds[item].scratchOffset = scratchBytes;
        scratchBytes = alignUp(scratchBytes + sizes.buildScratchSize, scratchAlignment);
        return structure;
    };
    for (size_t b = 0; b < toBuild.size(); ++b) {
        const AccelerationGeometry& g = in.geometries[toBuild[b]];
        VkAccelerationStructureGeometryKHR& geometry = builds[b].geometry;
        if (g.kind == GeometryKind::Triangles) {
            // Three vec4 per TrianglePrim: non-indexed vertices at a 16-byte stride (w is ignored).
            geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
            geometry.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
            auto& t = geometry.geometry.triangles;
            t = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
            t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
            t.vertexData.deviceAddress = in.triangleAddress + VkDeviceAddress(g.primOffset) * sizeof(gpu::TrianglePrim);
            t.vertexStride = sizeof(gpu::vec4);
            t.maxVertex = 3 * g.primCount - 1;
            t.indexType = VK_INDEX_TYPE_NONE_KHR;
        } else {
            // Not opaque: each candidate is confirmed by Ripple's own intersection test in the kernel.
            geometry.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
            auto& a = geometry.geometry.aabbs;
            a = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR};
            a.data.deviceAddress = boxBuffer.address() + boxOffset[toBuild[b]];
            a.stride = sizeof(VkAabbPositionsKHR);
        }
        VkAccelerationStructureBuildGeometryInfoKHR& info = builds[b].info;
        info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
        info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
        info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
        info.geometryCount = 1;
        info.pGeometries = &geometry;
        builds[b].range = {g.primCount, 0, 0, 0};
        blas_[toBuild[b]] = sizeAndCreate(info, g.primCount, b, geometryLabel(g.kind, uint32_t(toBuild[b])) + " BLAS");
    }

    // 2. The TLAS: one instance record per InstancePrim, custom index = its slot.
    const auto instanceCount = static_cast<uint32_t>(in.instances.size());
    std::vector<VkAccelerationStructureInstanceKHR> records(instanceCount);
    for (uint32_t slot = 0; slot < instanceCount; ++slot) {
        const gpu::InstancePrim& prim = in.instances[slot];
        VkAccelerationStructureInstanceKHR& r = records[slot];
        static_assert(sizeof(r.transform.matrix) == sizeof(prim.objectToWorld));  // rows of 3x4, both
        std::memcpy(r.transform.matrix, prim.objectToWorld, sizeof(r.transform.matrix));
        r.instanceCustomIndex = slot;
        r.mask = 0xFF;
        r.instanceShaderBindingTableRecordOffset = 0;
        r.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
        r.accelerationStructureReference = blas_[in.instanceGeometry[slot]]->address;
    }
    vk::Buffer instanceBuffer;
    const size_t tlasItem = toBuild.size();
    VkAccelerationStructureBuildGeometryInfoKHR& tlasInfo = builds[tlasItem].info;
    if (instanceCount > 0) {
        instanceBuffer = vk::Buffer(context, records.size() * sizeof(records[0]), "TLAS instance records", kBuildInput);
        instanceBuffer.upload(records.data(), instanceBuffer.size());
        VkAccelerationStructureGeometryKHR& geometry = builds[tlasItem].geometry;
        geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
        geometry.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
        geometry.geometry.instances.data.deviceAddress = instanceBuffer.address();
        tlasInfo.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
        tlasInfo.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
        tlasInfo.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
        tlasInfo.geometryCount = 1;
        tlasInfo.pGeometries = &geometry;
        builds[tlasItem].range = {instanceCount, 0, 0, 0};
        tlas_ = sizeAndCreate(tlasInfo, instanceCount, tlasItem, "scene TLAS");
        tlasAddress_ = tlas_->address;
    }

    // 3. Scratch, then the builds: BLASes together, a barrier, the TLAS that reads them.
    if (!toBuild.empty() || tlas_) {
        vk::Buffer scratch(context, scratchBytes + scratchAlignment, "acceleration structure scratch");
        const VkDeviceAddress scratchBase = alignUp(scratch.address(), scratchAlignment);
        std::vector<VkAccelerationStructureBuildGeometryInfoKHR> infos;  // the BLAS builds, contiguous
        std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePointers;
        for (Build& build : builds) {
            build.info.scratchData.deviceAddress = scratchBase + build.scratchOffset;
            rangePointers.push_back(&build.range);
            if (&build != &builds[tlasItem]) infos.push_back(build.info);
        }
        context.submitAndWait([&](VkCommandBuffer cmd) {
            VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
            barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
            if (!toBuild.empty()) {
                fn.cmdBuild(cmd, static_cast<uint32_t>(infos.size()), infos.data(), rangePointers.data());
                vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                     VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &barrier, 0, nullptr,
                                     0, nullptr);
            }
            if (tlas_) {
                fn.cmdBuild(cmd, 1, &tlasInfo, &rangePointers[tlasItem]);
                vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                     VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
            }
        });
    }
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

AccelerationStructures::~AccelerationStructures() = default;

uint64_t AccelerationStructures::bytes() const {
    uint64_t total = tlas_ ? tlas_->storage.size() : 0;
    for (const auto& b : blas_)
        if (b) total += b->storage.size();
    return total;
}

}  // namespace ripple::core
