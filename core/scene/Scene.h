// The flat GPU scene: validates a SceneDescription (skipping and counting bad primitives, attributes,
// materials, textures and lights), builds a BLAS per mesh, sphere, cylinder or cone set and a TLAS over
// instances, and uploads everything the trace and shading kernels read (shaders/shared/scene.h).
//
// Rebuilding only what changed: pass the Scene built from the previous state of the world as `previous`.
// Each geometry whose GeometryIdentity has a nonzero key and the same (key, version) as a geometry of
// `previous` (of the same kind, built with the same bvh::BuildOptions) reuses that geometry's validation
// and BLAS instead of building them again; each volume whose voxelIdentity matches one of `previous`'s
// reuses its device buffer of voxels (a transfer-function edit uploads none); everything else (attributes,
// TLAS, materials, transfer-function tables, majorants, upload) is redone. `previous` is only read during
// construction and may be destroyed afterwards.
//
// With ray-query traversal (core/render/Traversal.h; Auto resolves as the trace kernels do) the Scene also
// builds Vulkan acceleration structures over the same primitives (AccelerationStructures.h); a reused
// geometry reuses its BLAS from `previous` when that Scene has one. Its BVH4 is built either way.
#pragma once

#include "core/bvh/BinnedSahBuilder.h"
#include "core/render/Traversal.h"
#include "core/scene/PreparedGeometry.h"
#include "core/scene/SceneDescription.h"
#include "core/vk/Buffer.h"
#include "shaders/shared/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace ripple::core {

class AccelerationStructures;
struct VolumeVoxels;

// What validation dropped or repaired, and why; nothing bad ever reaches a kernel.
struct SceneReport {
    uint64_t trianglesKept = 0;
    uint64_t trianglesSkipped = 0;     // NaN/Inf vertex, index out of range, or zero area
    uint64_t spheresKept = 0;
    uint64_t spheresSkipped = 0;       // NaN/Inf center, radius <= 0 or non-finite
    uint64_t cylindersKept = 0;
    uint64_t cylindersSkipped = 0;     // NaN/Inf end, index out of range, zero length, bad radius
    uint64_t conesKept = 0;            // cone and curve segments
    uint64_t conesSkipped = 0;         // as cylinders; radii may be 0 at one end
    uint64_t isoCellsKept = 0;         // (cell, isovalue) pairs an iso-surface crosses
    uint64_t isoCellsSkipped = 0;      // cells with a NaN or Inf voxel
    uint64_t instancesKept = 0;
    uint64_t instancesSkipped = 0;     // empty geometry, bad reference, or non-finite/singular transform
    uint64_t attributesIgnored = 0;    // optional attributes with a wrong length or NaN/Inf values
    uint64_t materialsRepaired = 0;    // materials with a value replaced by its default or clamped
    uint64_t texturesSkipped = 0;      // wrong texel count or format
    uint64_t lightsKept = 0;
    uint64_t lightsSkipped = 0;        // NaN/Inf or negative values, zero direction or area
    uint64_t volumesKept = 0;
    uint64_t volumesSkipped = 0;       // NaN/Inf voxels or settings, wrong value count, bad transform
    uint64_t volumeVoxelsUploaded = 0; // kept volumes whose voxels were uploaded
    uint64_t volumeVoxelsReused = 0;   // ... whose voxel buffer was taken from `previous` (or an earlier volume)
    double volumeMajorantSeconds = 0.0; // the macrocell majorants, computed on the device
    uint64_t volumesCellByCell = 0;     // kept volumes with macrocells deep enough to cross cell by cell (VolumeMajorants.h)
    uint64_t blasBuilt = 0;
    uint64_t blasReused = 0;           // taken from `previous` (see the header comment)
    double blasBuildSeconds = 0.0;     // validation and BLAS builds (reused BLASes cost nothing)
    double tlasBuildSeconds = 0.0;
    // Ray-query traversal only: acceleration structures built and reused, their time (host setup, device
    // build and wait) and their bytes (also counted in gpuBytes).
    uint64_t accelerationStructuresBuilt = 0;  // BLASes
    uint64_t accelerationStructuresReused = 0;
    uint64_t accelerationStructurePrimitives = 0;  // in the BLASes built
    double accelerationStructureSeconds = 0.0;
    uint64_t accelerationStructureBytes = 0;
    uint64_t gpuBytes = 0;
    std::vector<std::string> messages; // one line per kind of problem per object, naming it
};

class Scene {
public:
    Scene(const vk::Context& context, const SceneDescription& description,
          const bvh::BuildOptions& buildOptions = {}, const Scene* previous = nullptr,
          Traversal traversal = Traversal::Auto);
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;

    const SceneReport& report() const { return report_; }
    VkDeviceAddress descAddress() const { return desc_.address(); }
    // The volumes' float array as VolumeTable laid it out, majorants filled in (for tests).
    const vk::Buffer& volumeData() const { return volumeData_; }
    uint32_t instanceCount() const { return instanceCount_; }
    uint32_t lightCount() const { return lightCount_; }
    // FrameConstants.ambient.w for an ambient light of this radiance (ambientLightChance in LightTable.h).
    float ambientLightChance(const glm::vec3& ambient) const;
    // Software or RayQuery: whether this scene has acceleration structures for ray-query kernels.
    Traversal traversal() const { return traversal_; }
    // FEATURE_* bits (shaders/shared/features.h) of what this scene holds: geometry kinds of its kept
    // instances, textures, emission, alpha and light kinds. The frame adds its own (core/render/FeatureSet.h).
    uint32_t features() const { return features_; }
    const bvh::Aabb& bounds() const { return bounds_; }
    // Where this scene's geometry and volumes lie: at most kMaxRegions world boxes covering every kept
    // instance and volume (bvh::clusterBoxes), empty for an empty scene. What a data-parallel rank tells
    // the others, so rays are sent only where they can meet something (mpi/BoundsExchange).
    static constexpr size_t kMaxRegions = 64;
    const std::vector<bvh::Aabb>& regions() const { return regions_; }
    // This scene's own emissive triangles as light records (what a data-parallel rank shares).
    const std::vector<gpu::LightRecord>& triangleLights() const { return triangleLights_; }

private:
    SceneReport report_;
    bvh::Aabb bounds_;
    std::vector<bvh::Aabb> regions_;
    uint32_t instanceCount_ = 0;
    uint32_t lightCount_ = 0;
    float lightSceneRadius_ = 1.0f;  // what the lights' selection powers were computed with
    float lightPowerTotal_ = 0.0f;
    uint32_t features_ = 0;
    std::vector<gpu::LightRecord> triangleLights_;
    // The validated geometries with an identity, kept so a later Scene can reuse them.
    std::vector<std::shared_ptr<const PreparedGeometry>> reusable_;
    Traversal traversal_ = Traversal::Software;
    std::unique_ptr<AccelerationStructures> accelerationStructures_;  // RayQuery only
    // Each kept volume's voxels (in VolumeTable record order), shared with the scenes that reuse them.
    std::vector<std::shared_ptr<const VolumeVoxels>> volumeVoxels_;
    // The words of each unstructured mesh an iso-surface is drawn in (IsoCellPrim addresses them).
    std::vector<std::pair<std::shared_ptr<const UnstructuredGrid>, vk::Buffer>> isoMeshes_;
    vk::Buffer nodes_, triangles_, spheres_, cylinders_, cones_, isoCells_, instances_, instanceShading_, geometries_, primSlots_,
        vertexIndices_, attributes_, materials_, textures_, texels_, lights_, volumes_, volumeData_, desc_;
};

}  // namespace ripple::core
