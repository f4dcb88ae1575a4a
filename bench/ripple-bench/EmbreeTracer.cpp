// Embree 3 side of ripple-bench: scene build and single-ray traversal over gpu::Ray arrays.
#include "bench/ripple-bench/EmbreeTracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstring>
#include <stdexcept>

namespace ripple::bench {

namespace {

// Rays per task: large enough to amortise task overhead, small enough to balance coherent and
// incoherent regions of an image across threads.
constexpr size_t kRaysPerTask = 256;

RTCRay toEmbree(const gpu::Ray& r) {
    RTCRay e{};
    e.org_x = r.origin.x;
    e.org_y = r.origin.y;
    e.org_z = r.origin.z;
    e.tnear = r.origin.w;
    e.dir_x = r.direction.x;
    e.dir_y = r.direction.y;
    e.dir_z = r.direction.z;
    e.tfar = r.direction.w;
    e.mask = ~0u;
    return e;
}

}  // namespace

EmbreeTracer::EmbreeTracer() {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed (error " +
                                           std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
}

EmbreeTracer::~EmbreeTracer() {
    releaseScene();
    rtcReleaseDevice(device_);
}

void EmbreeTracer::releaseScene() {
    if (scene_) rtcReleaseScene(scene_);
    scene_ = nullptr;
}

void EmbreeTracer::throwOnError(const char* what) const {
    const RTCError error = rtcGetDeviceError(device_);
    if (error != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                                                          std::to_string(int(error)) + ")");
}

void EmbreeTracer::build(const core::TriangleMesh& mesh) {
    releaseScene();
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);

    // Embree's own buffers carry the tail padding its SIMD loads need; sharing glm::vec3 arrays would not.
    const size_t vertexCount = mesh.positions.size();
    void* vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                             3 * sizeof(float), vertexCount);
    const size_t triangleCount = mesh.indices.empty() ? vertexCount / 3 : mesh.indices.size();
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangleCount));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geometry);
        throwOnError("allocating geometry buffers");
        throw std::runtime_error("Embree: no geometry buffers for " + std::to_string(triangleCount) + " triangles");
    }
    std::memcpy(vertices, mesh.positions.data(), vertexCount * 3 * sizeof(float));
    if (mesh.indices.empty()) {
        for (size_t i = 0; i < triangleCount * 3; ++i) indices[i] = uint32_t(i);
    } else {
        std::memcpy(indices, mesh.indices.data(), triangleCount * 3 * sizeof(uint32_t));
    }

    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    throwOnError("building the scene");
}

void EmbreeTracer::traceClosest(std::span<const gpu::Ray> rays, std::span<gpu::Hit> hits) const {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kRaysPerTask), [&](const auto& range) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t i = range.begin(); i != range.end(); ++i) {
            RTCRayHit rayHit{};
            rayHit.ray = toEmbree(rays[i]);
            rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene_, &context, &rayHit);
            gpu::Hit& h = hits[i];
            if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
                h = gpu::Hit{rays[i].direction.w, 0.0f, 0.0f, 0u, 0u, gpu::HIT_MISS};
            } else {
                h = gpu::Hit{rayHit.ray.tfar, rayHit.hit.u, rayHit.hit.v, 0u, rayHit.hit.primID, gpu::HIT_FOUND};
            }
        }
    });
}

void EmbreeTracer::traceAny(std::span<const gpu::Ray> rays, std::span<uint32_t> occluded) const {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kRaysPerTask), [&](const auto& range) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t i = range.begin(); i != range.end(); ++i) {
            RTCRay ray = toEmbree(rays[i]);
            rtcOccluded1(scene_, &context, &ray);
            // Embree marks an occluded ray by setting tfar to -inf.
            occluded[i] = ray.tfar < 0.0f ? gpu::HIT_FOUND : gpu::HIT_MISS;
        }
    });
}

std::string EmbreeTracer::version() { return RTC_VERSION_STRING; }

}  // namespace ripple::bench
