// Vulkan acceleration structures for the ray-query traversal back-end: one BLAS per geometry a Scene
// keeps (triangles as native triangle geometry read straight from the uploaded TrianglePrim array;
// spheres, cylinders and cones as AABB geometry in the same leaf order), and a TLAS over the instances
// whose custom index is the instance's slot in SceneDesc.instances. Built on the device in one submission.
// A BLAS of a geometry that a Scene reuses from its `previous` is taken from the previous Scene's set.
#pragma once

#include "core/scene/PreparedGeometry.h"
#include "core/vk/Buffer.h"
#include "shaders/shared/scene.h"

#include <memory>
#include <span>
#include <vector>

namespace ripple::core {

// One geometry as laid out in the flat scene: its primitives are prims[primOffset, primOffset + primCount)
// of its kind's array.
struct AccelerationGeometry {
    std::shared_ptr<const PreparedGeometry> prepared;  // identifies the geometry for reuse
    GeometryKind kind = GeometryKind::Triangles;
    uint32_t primOffset = 0;
    uint32_t primCount = 0;
};

// The flat primitive arrays (host copies; triangles are read on the device from `triangleAddress`, a
// buffer created with VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR).
struct AccelerationInputs {
    std::span<const AccelerationGeometry> geometries;
    VkDeviceAddress triangleAddress = 0;
    std::span<const gpu::SpherePrim> spheres;
    std::span<const gpu::CylinderPrim> cylinders;
    std::span<const gpu::ConePrim> cones;
    std::span<const gpu::IsoCellPrim> isoCells;
    std::span<const gpu::InstancePrim> instances;  // TLAS order
    std::span<const uint32_t> instanceGeometry;    // per instance: its index in `geometries`
};

class AccelerationStructures {
public:
    AccelerationStructures(const vk::Context& context, const AccelerationInputs& inputs,
                           const AccelerationStructures* previous = nullptr);
    ~AccelerationStructures();
    AccelerationStructures(const AccelerationStructures&) = delete;
    AccelerationStructures& operator=(const AccelerationStructures&) = delete;

    // Device address of the TLAS; 0 when there are no instances (every ray misses).
    VkDeviceAddress tlasAddress() const { return tlasAddress_; }
    uint64_t bytes() const;        // storage of the TLAS and of every BLAS it references
    uint64_t blasBuilt() const { return blasBuilt_; }
    uint64_t blasReused() const { return blasReused_; }
    uint64_t primitivesBuilt() const { return primitivesBuilt_; }  // in the BLASes built (not reused)
    double buildSeconds() const { return buildSeconds_; }          // host setup, device build and wait

    struct Structure;  // an acceleration structure and its storage buffer

private:
    const vk::Context& context_;
    // Per geometry (null for an empty one), shared with later Scenes that reuse it.
    std::vector<std::shared_ptr<const PreparedGeometry>> keys_;
    std::vector<std::shared_ptr<Structure>> blas_;
    std::unique_ptr<Structure> tlas_;
    VkDeviceAddress tlasAddress_ = 0;
    uint64_t blasBuilt_ = 0, blasReused_ = 0, primitivesBuilt_ = 0;
    double buildSeconds_ = 0.0;
};

}  // namespace ripple::core
