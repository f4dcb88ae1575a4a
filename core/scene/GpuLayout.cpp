// Compile-time checks that the C++ view of every struct in shaders/shared/*.h has the std430 layout the
// kernels read. A failing assert here means a shared header was edited without keeping the two in step.
#include "shaders/shared/bvh.h"
#include "shaders/shared/bvh4.h"
#include "shaders/shared/material.h"
#include "shaders/shared/path.h"
#include "shaders/shared/ray.h"
#include "shaders/shared/scene.h"
#include "shaders/shared/volume.h"

#include <cstddef>

namespace ripple::gpu {

static_assert(sizeof(vec4) == 16);
static_assert(sizeof(BvhNode) == 64);
static_assert(offsetof(BvhNode, rightMin) == 32);
static_assert(sizeof(Bvh4Node) == 112);
static_assert(offsetof(Bvh4Node, minZ) == 64);
static_assert(offsetof(Bvh4Node, children) == 96);
static_assert(sizeof(Bvh4CompressedNode) == 64);
static_assert(offsetof(Bvh4CompressedNode, children) == 48);
static_assert(sizeof(Bvh4TraceParams) == 48);
static_assert(offsetof(Bvh4TraceParams, rayCount) == 32);

static_assert(sizeof(TrianglePrim) == 48);
static_assert(sizeof(SpherePrim) == 32);
static_assert(offsetof(SpherePrim, primId) == 16);
static_assert(sizeof(CylinderPrim) == 48);
static_assert(offsetof(CylinderPrim, primId) == 32);
static_assert(sizeof(InstancePrim) == 112);
static_assert(offsetof(InstancePrim, objectToWorld) == 48);
static_assert(offsetof(InstancePrim, blasNodeOffset) == 96);
static_assert(offsetof(InstancePrim, instanceId) == 108);
static_assert(sizeof(InstanceShading) == 128);
static_assert(offsetof(InstanceShading, attributeOffset) == 112);
static_assert(offsetof(InstanceShading, geometry) == 96);
static_assert(offsetof(InstanceShading, userInstanceId) == 108);
static_assert(sizeof(GeometryRecord) == 64);
static_assert(offsetof(GeometryRecord, attributeRates) == 48);
static_assert(offsetof(GeometryRecord, tangentOffset) == 52);
static_assert(offsetof(GeometryRecord, attributeOffset) == 32);
static_assert(offsetof(GeometryRecord, trianglesPerPrimitive) == 28);
static_assert(sizeof(ConePrim) == 48);
static_assert(offsetof(ConePrim, primId) == 32);
static_assert(sizeof(SceneDesc) == 192);
static_assert(offsetof(SceneDesc, isoCells) == 184);
static_assert(sizeof(IsoCellPrim) == 80);
static_assert(offsetof(IsoCellPrim, primId) == 64);
static_assert(offsetof(SceneDesc, volumeData) == 176);
static_assert(sizeof(VolumeRecord) == 144);
static_assert(offsetof(VolumeRecord, objectId) == 120);
static_assert(offsetof(VolumeRecord, voxels) == 128);
static_assert(offsetof(VolumeRecord, dimX) == 80);
static_assert(offsetof(SceneDesc, accelerationStructure) == 160);
static_assert(offsetof(SceneDesc, originUnit) == 136);
static_assert(offsetof(SceneDesc, lightPowerTotal) == 144);
static_assert(offsetof(SceneDesc, cones) == 128);
static_assert(offsetof(SceneDesc, lights) == 104);
static_assert(offsetof(SceneDesc, instanceCount) == 112);

static_assert(sizeof(MaterialRecord) == 96);
static_assert(offsetof(MaterialRecord, kind) == 32);
static_assert(offsetof(MaterialRecord, metallic) == 48);
static_assert(offsetof(MaterialRecord, transmission) == 64);
static_assert(offsetof(MaterialRecord, metallicTexture) == 80);
static_assert(sizeof(TextureRecord) == 208);
static_assert(offsetof(TextureRecord, inTransform) == 48);
static_assert(offsetof(TextureRecord, inOffset) == 112);
static_assert(offsetof(TextureRecord, outTransform) == 128);
static_assert(offsetof(TextureRecord, outOffset) == 192);
static_assert(sizeof(LightRecord) == 96);
static_assert(offsetof(LightRecord, distribution) == 92);
static_assert(offsetof(LightRecord, kind) == 80);

static_assert(sizeof(PathState) == 32);
static_assert(offsetof(PathState, slot) == 16);
static_assert(sizeof(ShadowRequest) == 32);
static_assert(sizeof(PathCounters) == 112);
static_assert(offsetof(PathCounters, parkedMarches) == 104);
static_assert(offsetof(PathCounters, realCollisions) == 80);
static_assert(offsetof(PathCounters, pathGroups) == 32);
static_assert(sizeof(QueueAdvanceParams) == 24);
static_assert(sizeof(FrameConstants) == 208);
static_assert(offsetof(FrameConstants, latestSample) == 196);
static_assert(offsetof(FrameConstants, shading) == 184);
static_assert(offsetof(FrameConstants, phaseAnisotropy) == 176);
static_assert(offsetof(FrameConstants, cameraFar) == 180);
static_assert(offsetof(FrameConstants, width) == 112);
static_assert(offsetof(FrameConstants, sampleRadiance) == 128);
static_assert(offsetof(FrameConstants, counters) == 160);
static_assert(sizeof(SurfaceRecord) == 128);
static_assert(offsetof(SurfaceRecord, primitiveId) == 112);
static_assert(offsetof(SurfaceRecord, layers) == 80);
static_assert(offsetof(SurfaceRecord, status) == 96);
static_assert(sizeof(StageParams) == 128);
static_assert(offsetof(StageParams, volumeParking) == 120);
static_assert(offsetof(StageParams, count) == 88);
static_assert(offsetof(StageParams, mode) == 104);
static_assert(sizeof(StageParams) <= 128, "push constants: 128 bytes is all Vulkan guarantees");

static_assert(sizeof(Ray) == 32);
static_assert(sizeof(Hit) == 24);
static_assert(offsetof(Hit, status) == 20);
static_assert(offsetof(TraversalState, best) == 16);
static_assert(offsetof(TraversalState, stack) == 48);
static_assert(sizeof(TraversalState) == 48 + 4 * TRAVERSAL_STACK_SIZE);
static_assert(sizeof(ResumeHeader) == 16);
static_assert(sizeof(VolumeParked) == 48);
static_assert(sizeof(MajorantParams) == 24);
static_assert(offsetof(MajorantParams, volume) == 16);
static_assert(offsetof(VolumeParked, albedo) == 16);
static_assert(sizeof(VolumeParkingHeader) == 16 * (VOLUME_MAX_RESUME_ROUNDS + 1) + 16);
static_assert(sizeof(TraceParams) == 64);
static_assert(offsetof(TraceParams, rayCount) == 48);
static_assert(sizeof(TraceParams) <= 128, "push constants: 128 bytes is all Vulkan guarantees");

}  // namespace ripple::gpu
