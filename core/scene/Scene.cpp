// Validation of host geometry, BLAS/TLAS construction and upload of the flat GPU scene.
#include "core/scene/Scene.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <bit>
#include <chrono>
#include <cmath>

namespace ripple::core {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A geometry's valid primitives (input indices) and boxes, before its BLAS is built.
struct PreparedGeometry {
    GeometryKind kind = GeometryKind::Triangles;
    uint32_t index = 0;
    std::vector<uint32_t> validPrims;
    std::vector<bvh::Aabb> boxes;
    bvh::Bvh blas;
    uint32_t nodeOffset = 0;
    uint32_t primOffset = 0;
};

std::string label(GeometryKind kind, uint32_t index) {
    return (kind == GeometryKind::Triangles ? "mesh " : "sphere set ") + std::to_string(index);
}

void prepareMesh(const TriangleMesh& mesh, PreparedGeometry& out, SceneReport& report) {
    const uint64_t positionCount = mesh.positions.size();
    const uint64_t triangleCount = mesh.indices.empty() ? positionCount / 3 : mesh.indices.size();
    uint64_t badIndex = 0, nonFinite = 0, zeroArea = 0;
    for (uint64_t t = 0; t < triangleCount; ++t) {
        const glm::uvec3 idx = mesh.indices.empty() ? glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2) : mesh.indices[t];
        if (idx.x >= positionCount || idx.y >= positionCount || idx.z >= positionCount) { ++badIndex; continue; }
        const glm::vec3 &a = mesh.positions[idx.x], &b = mesh.positions[idx.y], &c = mesh.positions[idx.z];
        if (!finite(a) || !finite(b) || !finite(c)) { ++nonFinite; continue; }
        const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
        if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) { ++zeroArea; continue; }
        bvh::Aabb box;
        box.extend(a);
        box.extend(b);
        box.extend(c);
        out.validPrims.push_back(static_cast<uint32_t>(t));
        out.boxes.push_back(box);
    }
    const std::string name = label(out.kind, out.index);
    if (badIndex) report.messages.push_back(name + ": skipped " + std::to_string(badIndex) + " triangle(s) with an index out of range (" + std::to_string(positionCount) + " positions)");
    if (nonFinite) report.messages.push_back(name + ": skipped " + std::to_string(nonFinite) + " triangle(s) with a NaN or Inf vertex");
    if (zeroArea) report.messages.push_back(name + ": skipped " + std::to_string(zeroArea) + " zero-area triangle(s)");
    report.trianglesSkipped += badIndex + nonFinite + zeroArea;
}

void prepareSpheres(const SphereSet& set, PreparedGeometry& out, SceneReport& report) {
    uint64_t badRadius = 0, nonFinite = 0;
    const std::string name = label(out.kind, out.index);
    if (set.radii.size() != 1 && set.radii.size() != set.centers.size()) {
        report.messages.push_back(name + ": " + std::to_string(set.radii.size()) + " radii for " +
                                  std::to_string(set.centers.size()) + " centers (need 1 or one each); set skipped");
        report.spheresSkipped += set.centers.size();
        return;
    }
    for (uint32_t i = 0; i < set.centers.size(); ++i) {
        const float r = set.radii.size() == 1 ? set.radii[0] : set.radii[i];
        if (!finite(set.centers[i])) { ++nonFinite; continue; }
        if (!(std::isfinite(r) && r > 0.0f)) { ++badRadius; continue; }
        out.validPrims.push_back(i);
        out.boxes.push_back({set.centers[i] - glm::vec3(r), set.centers[i] + glm::vec3(r)});
    }
    if (nonFinite) report.messages.push_back(name + ": skipped " + std::to_string(nonFinite) + " sphere(s) with a NaN or Inf center");
    if (badRadius) report.messages.push_back(name + ": skipped " + std::to_string(badRadius) + " sphere(s) with a radius that is not finite and positive");
    report.spheresSkipped += badRadius + nonFinite;
}

bool affineAndInvertible(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;
    return std::abs(glm::determinant(glm::dmat3(glm::mat3(m)))) > 1e-30;
}

// Rows of the affine part of a column-major matrix, as the kernels read them.
void storeRows(const glm::dmat4& m, gpu::vec4 rows[3]) {
    for (int r = 0; r < 3; ++r)
        rows[r] = gpu::vec4(static_cast<float>(m[0][r]), static_cast<float>(m[1][r]), static_cast<float>(m[2][r]),
                            static_cast<float>(m[3][r]));
}

bvh::Aabb transformBox(const bvh::Aabb& box, const glm::mat4& m) {
    bvh::Aabb out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                          (corner & 4) ? box.hi.z : box.lo.z);
        out.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    return out;
}

}  // namespace

Scene::Scene(const vk::Context& context, const SceneDescription& description, const bvh::BuildOptions& buildOptions) {
    // 1. Validate every referenced geometry; what cannot be traced is skipped and reported.
    std::vector<PreparedGeometry> geometries;
    std::vector<int64_t> meshSlot(description.meshes.size(), -1), sphereSlot(description.sphereSets.size(), -1);
    struct ValidInstance { uint32_t instanceId; uint32_t geometry; glm::mat4 transform; };
    std::vector<ValidInstance> valid;
    for (uint32_t i = 0; i < description.instances.size(); ++i) {
        const InstanceDescription& inst = description.instances[i];
        if (inst.geometry.kind != GeometryKind::Triangles && inst.geometry.kind != GeometryKind::Spheres) {
            report_.messages.push_back("instance " + std::to_string(i) + ": unknown geometry kind " +
                                       std::to_string(static_cast<uint32_t>(inst.geometry.kind)) + "; skipped");
            ++report_.instancesSkipped;
            continue;
        }
        const bool isMesh = inst.geometry.kind == GeometryKind::Triangles;
        auto& slots = isMesh ? meshSlot : sphereSlot;
        const std::string name = label(inst.geometry.kind, inst.geometry.index);
        if (inst.geometry.index >= slots.size()) {
            report_.messages.push_back("instance " + std::to_string(i) + ": references " + name + ", which does not exist; skipped");
            ++report_.instancesSkipped;
            continue;
        }
        if (!affineAndInvertible(inst.transform)) {
            report_.messages.push_back("instance " + std::to_string(i) + ": transform is not finite, affine and invertible; skipped");
            ++report_.instancesSkipped;
            continue;
        }
        int64_t& slot = slots[inst.geometry.index];
        if (slot < 0) {
            PreparedGeometry g;
            g.kind = inst.geometry.kind;
            g.index = inst.geometry.index;
            if (isMesh) prepareMesh(description.meshes[g.index], g, report_);
            else prepareSpheres(description.sphereSets[g.index], g, report_);
            (isMesh ? report_.trianglesKept : report_.spheresKept) += g.validPrims.size();
            slot = static_cast<int64_t>(geometries.size());
            geometries.push_back(std::move(g));
        }
        if (geometries[slot].validPrims.empty()) {
            report_.messages.push_back("instance " + std::to_string(i) + ": " + name + " has no valid primitives; skipped");
            ++report_.instancesSkipped;
            continue;
        }
        valid.push_back({i, static_cast<uint32_t>(slot), inst.transform});
    }
    report_.instancesKept = valid.size();

    // 2. One BLAS per geometry (each build is itself parallel), then the TLAS over instance boxes.
    auto start = Clock::now();
    for (auto& g : geometries)
        if (!g.validPrims.empty()) g.blas = bvh::buildBinnedSah(g.boxes, buildOptions);
    report_.blasBuildSeconds = secondsSince(start);

    std::vector<bvh::Aabb> instanceBoxes;
    for (const auto& v : valid) instanceBoxes.push_back(transformBox(geometries[v.geometry].blas.bounds, v.transform));
    start = Clock::now();
    bvh::BuildOptions tlasOptions = buildOptions;
    tlasOptions.maxLeafSize = 1;  // the kernel enters one instance per TLAS leaf entry
    const bvh::Bvh tlas = bvh::buildBinnedSah(instanceBoxes, tlasOptions);
    report_.tlasBuildSeconds = secondsSince(start);
    bounds_ = tlas.bounds;

    // 3. Flatten: TLAS nodes first, then each BLAS; primitives and instances in leaf order.
    std::vector<gpu::BvhNode> nodes = tlas.nodes;
    std::vector<gpu::TrianglePrim> triangles;
    std::vector<gpu::SpherePrim> spheres;
    for (auto& g : geometries) {
        if (g.validPrims.empty()) continue;
        g.nodeOffset = static_cast<uint32_t>(nodes.size());
        nodes.insert(nodes.end(), g.blas.nodes.begin(), g.blas.nodes.end());
        if (g.kind == GeometryKind::Triangles) {
            g.primOffset = static_cast<uint32_t>(triangles.size());
            const TriangleMesh& mesh = description.meshes[g.index];
            for (uint32_t slot : g.blas.primOrder) {
                const uint32_t t = g.validPrims[slot];
                const glm::uvec3 idx = mesh.indices.empty() ? glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2) : mesh.indices[t];
                triangles.push_back({gpu::vec4(mesh.positions[idx.x], std::bit_cast<float>(t)),
                                     gpu::vec4(mesh.positions[idx.y], 0.0f), gpu::vec4(mesh.positions[idx.z], 0.0f)});
            }
        } else {
            g.primOffset = static_cast<uint32_t>(spheres.size());
            const SphereSet& set = description.sphereSets[g.index];
            for (uint32_t slot : g.blas.primOrder) {
                const uint32_t s = g.validPrims[slot];
                const float r = set.radii.size() == 1 ? set.radii[0] : set.radii[s];
                spheres.push_back({gpu::vec4(set.centers[s], r), s, 0, 0, 0});
            }
        }
    }
    std::vector<gpu::InstancePrim> instances;
    for (uint32_t slot : tlas.primOrder) {
        const ValidInstance& v = valid[slot];
        const PreparedGeometry& g = geometries[v.geometry];
        gpu::InstancePrim prim{};
        const glm::dmat4 toWorld(v.transform);
        storeRows(glm::inverse(toWorld), prim.worldToObject);
        storeRows(toWorld, prim.objectToWorld);
        prim.blasNodeOffset = g.nodeOffset;
        prim.primOffset = g.primOffset;
        prim.geometryKind = g.kind == GeometryKind::Triangles ? gpu::GEOMETRY_TRIANGLES : gpu::GEOMETRY_SPHERES;
        prim.instanceId = v.instanceId;
        instances.push_back(prim);
    }
    instanceCount_ = static_cast<uint32_t>(instances.size());

    // 4. Upload. Empty arrays still get a (tiny) buffer so every address in SceneDesc is valid.
    auto upload = [&](vk::Buffer& buffer, const auto& items, const char* name) {
        const VkDeviceSize bytes = items.size() * sizeof(items[0]);
        buffer = vk::Buffer(context, bytes, name);
        buffer.upload(items.data(), bytes);
        report_.gpuBytes += bytes;
    };
    upload(nodes_, nodes, "scene BVH nodes");
    upload(triangles_, triangles, "scene triangles");
    upload(spheres_, spheres, "scene spheres");
    upload(instances_, instances, "scene instances");
    const std::vector<gpu::SceneDesc> desc{{nodes_.address(), triangles_.address(), spheres_.address(),
                                            instances_.address(), instanceCount_, 0, 0, 0}};
    upload(desc_, desc, "scene descriptor");
}

}  // namespace ripple::core
