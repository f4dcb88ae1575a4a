// Assembly of the flat GPU scene: instances validated, geometries prepared (or reused from the previous
// Scene), TLAS built, primitives, shading attributes, materials and lights flattened and uploaded.
#include "core/scene/Scene.h"

#include "core/bvh/BoxClusters.h"

#include "core/bvh/Bvh4Collapse.h"
#include "core/bvh/Bvh4Compress.h"
#include "core/render/FeatureSet.h"
#include "core/scene/AccelerationStructures.h"
#include "core/scene/LightTable.h"
#include "core/scene/ShadingTables.h"
#include "core/scene/VolumeMajorants.h"
#include "core/scene/VolumeTable.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <functional>

namespace ripple::core {

// A volume's voxels (or unstructured mesh) on the device (VolumeRecord::voxels), with the identity that lets
// a later scene reuse them.
struct VolumeVoxels {
    GeometryIdentity identity;
    size_t bytes = 0;
    vk::Buffer buffer;
};

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool sameOptions(const bvh::BuildOptions& a, const bvh::BuildOptions& b) {
    return a.binCount == b.binCount && a.maxLeafSize == b.maxLeafSize && a.traversalCost == b.traversalCost &&
           a.parallelThreshold == b.parallelThreshold;
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

gpu::vec4 toVec4(const glm::vec2& v) { return gpu::vec4(v, 0.0f, 1.0f); }
gpu::vec4 toVec4(const glm::vec3& v) { return gpu::vec4(v, 0.0f); }
gpu::vec4 toVec4(const glm::vec4& v) { return v; }

// One geometry of this scene: its validated form and where its data landed in the flat arrays.
struct UsedGeometry {
    GeometryKind kind;
    uint32_t index;         // in the description's meshes, sphereSets or cylinderSets
    std::shared_ptr<const PreparedGeometry> prepared;
    uint32_t nodeOffset = 0;
    uint32_t primOffset = 0;
};

// Everything the kernels read, before upload.
struct FlatScene {
    std::vector<gpu::Bvh4Node> nodes;  // compressed at upload
    std::vector<gpu::TrianglePrim> triangles;
    std::vector<gpu::SpherePrim> spheres;
    std::vector<gpu::CylinderPrim> cylinders;
    std::vector<gpu::ConePrim> cones;
    std::vector<gpu::IsoCellPrim> isoCells;
    // Iso-surfaces of unstructured meshes: their prims [first, first + count) of isoCells take the device
    // address of `mesh`'s words once uploaded.
    struct IsoMesh {
        std::shared_ptr<const UnstructuredGrid> mesh;
        size_t first = 0, count = 0;
    };
    std::vector<IsoMesh> isoMeshes;
    std::vector<gpu::GeometryRecord> geometries;
    std::vector<uint32_t> primSlots;
    std::vector<uint32_t> vertexIndices;
    std::vector<gpu::vec4> attributes;
};

// Appends an optional attribute when it has exactly `expected` entries, all finite; otherwise names the
// problem and returns NO_ATTRIBUTE (the attribute is ignored).
template <class T>
uint32_t appendAttribute(const std::vector<T>& values, uint64_t expected, const std::string& what,
                         const std::string& owner, FlatScene& flat, SceneReport& report) {
    if (values.empty()) return gpu::NO_ATTRIBUTE;
    auto ignore = [&](const std::string& why) {
        report.messages.push_back(owner + ": " + what + " " + why + "; attribute ignored");
        ++report.attributesIgnored;
        return gpu::NO_ATTRIBUTE;
    };
    if (values.size() != expected)
        return ignore("has " + std::to_string(values.size()) + " entries, not " + std::to_string(expected));
    for (const T& v : values)
        for (int c = 0; c < T::length(); ++c)
            if (!std::isfinite(v[c])) return ignore("holds NaN or Inf");
    const auto offset = static_cast<uint32_t>(flat.attributes.size());
    for (const T& v : values) flat.attributes.push_back(toVec4(v));
    return offset;
}

// Appends a geometry's attribute0..3 and sets the record's offsets and rates. Per-vertex values of a
// segment shape (`ends` given: a primitive's two vertex indices) are stored as a pair per primitive, the
// form the kernels interpolate along the axis.
void appendGeometryAttributes(const GeometryAttributes& attributes, uint64_t vertices, uint64_t primitives,
                              const std::function<glm::uvec2(uint64_t)>& ends, const std::string& owner,
                              FlatScene& flat, gpu::GeometryRecord& record, SceneReport& report) {
    record.attributeRates = 0;
    for (size_t a = 0; a < attributes.size(); ++a) {
        const GeometryAttribute& attribute = attributes[a];
        const std::vector<glm::vec4>* stored = &attribute.values;
        uint64_t expected = attribute.rate == GeometryAttribute::Rate::Vertex      ? vertices
                            : attribute.rate == GeometryAttribute::Rate::Primitive ? primitives
                                                                                   : 1;
        std::vector<glm::vec4> pairs;
        if (attribute.rate == GeometryAttribute::Rate::Vertex && ends && attribute.values.size() == vertices) {
            const glm::vec4 missing(0.0f, 0.0f, 0.0f, 1.0f);
            for (uint64_t p = 0; p < primitives; ++p) {
                const glm::uvec2 e = ends(p);
                pairs.push_back(e.x < vertices ? attribute.values[e.x] : missing);
                pairs.push_back(e.y < vertices ? attribute.values[e.y] : missing);
            }
            stored = &pairs;
            expected = pairs.size();
        }
        record.attributeOffset[a] = appendAttribute(*stored, expected, "attribute" + std::to_string(a), owner, flat, report);
        record.attributeRates |= static_cast<uint32_t>(attribute.rate) << (2 * a);
    }
}

void flattenTriangles(const TriangleMesh& mesh, UsedGeometry& g, FlatScene& flat, gpu::GeometryRecord& record,
                      SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    for (uint32_t slot : p.blas.primOrder) {
        const uint32_t t = p.validPrims[slot];
        const glm::uvec3 idx = mesh.indices.empty() ? glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2) : mesh.indices[t];
        flat.triangles.push_back({gpu::vec4(mesh.positions[idx.x], std::bit_cast<float>(t)),
                                  gpu::vec4(mesh.positions[idx.y], 0.0f), gpu::vec4(mesh.positions[idx.z], 0.0f)});
    }
    const std::string name = geometryLabel(g.kind, g.index);
    const uint64_t vertices = mesh.positions.size();
    record.normalOffset = appendAttribute(mesh.normals, vertices, "normals", name, flat, report);
    record.colorOffset = appendAttribute(mesh.colors, vertices, "colors", name, flat, report);
    record.texcoordOffset = appendAttribute(mesh.texcoords, vertices, "texcoords", name, flat, report);
    record.tangentOffset = appendAttribute(mesh.tangents, vertices, "tangents", name, flat, report);
    record.primitiveColorOffset = appendAttribute(mesh.primitiveColors, p.inputPrimCount, "primitiveColors", name, flat, report);
    record.trianglesPerPrimitive = std::max(1u, mesh.trianglesPerPrimitive);
    appendGeometryAttributes(mesh.attributes, vertices, p.inputPrimCount / record.trianglesPerPrimitive, {}, name,
                             flat, record, report);
    bool perVertex = record.normalOffset != gpu::NO_ATTRIBUTE || record.colorOffset != gpu::NO_ATTRIBUTE ||
                     record.texcoordOffset != gpu::NO_ATTRIBUTE || record.tangentOffset != gpu::NO_ATTRIBUTE;
    for (size_t a = 0; a < mesh.attributes.size(); ++a)
        perVertex = perVertex || (record.attributeOffset[a] != gpu::NO_ATTRIBUTE &&
                                  mesh.attributes[a].rate == GeometryAttribute::Rate::Vertex);
    if (perVertex && !mesh.indices.empty()) {
        record.indexOffset = static_cast<uint32_t>(flat.vertexIndices.size());
        for (const glm::uvec3& idx : mesh.indices) flat.vertexIndices.insert(flat.vertexIndices.end(), {idx.x, idx.y, idx.z});
    }
}

void flattenSpheres(const SphereSet& set, UsedGeometry& g, FlatScene& flat, gpu::GeometryRecord& record,
                    SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    for (uint32_t slot : p.blas.primOrder) {
        const uint32_t s = p.validPrims[slot];
        flat.spheres.push_back({gpu::vec4(set.centers[s], radiusOf(set.radii, s)), s, 0, 0, 0});
    }
    const std::string name = geometryLabel(g.kind, g.index);
    record.colorOffset = appendAttribute(set.colors, p.inputPrimCount, "colors", name, flat, report);
    appendGeometryAttributes(set.attributes, p.inputPrimCount, p.inputPrimCount, {}, name, flat, record, report);
}

void flattenCylinders(const CylinderSet& set, UsedGeometry& g, FlatScene& flat, gpu::GeometryRecord& record,
                      SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    for (uint32_t slot : p.blas.primOrder) {
        const uint32_t c = p.validPrims[slot];
        const glm::uvec2 idx = cylinderIndices(set, c);
        const CapEnds caps = set.segmentCaps.empty() ? set.caps : set.segmentCaps[c];
        flat.cylinders.push_back({gpu::vec4(set.positions[idx.x], radiusOf(set.radii, c)),
                                  gpu::vec4(set.positions[idx.y], 0.0f), c, static_cast<uint32_t>(caps), 0, 0});
    }
    const std::string name = geometryLabel(g.kind, g.index);
    record.colorOffset = appendAttribute(set.colors, p.inputPrimCount, "colors", name, flat, report);
    appendGeometryAttributes(set.attributes, set.positions.size(), p.inputPrimCount,
                             [&](uint64_t c) { return cylinderIndices(set, c); }, name, flat, record, report);
}

void flattenCones(const ConeSet& set, UsedGeometry& g, FlatScene& flat, gpu::GeometryRecord& record,
                  SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    for (uint32_t slot : p.blas.primOrder) {
        const uint32_t c = p.validPrims[slot];
        const glm::uvec2 idx = coneIndices(set, c);
        const uint32_t flags = set.round                  ? gpu::CONE_ROUND
                               : set.segmentCaps.empty() ? static_cast<uint32_t>(set.caps)
                                                         : static_cast<uint32_t>(set.segmentCaps[c]);
        flat.cones.push_back({gpu::vec4(set.positions[idx.x], radiusOf(set.radii, idx.x)),
                              gpu::vec4(set.positions[idx.y], radiusOf(set.radii, idx.y)), c, flags, 0, 0});
    }
    const std::string name = geometryLabel(g.kind, g.index);
    record.colorOffset = appendAttribute(set.colors, p.inputPrimCount, "colors", name, flat, report);
    appendGeometryAttributes(set.attributes, set.positions.size(), p.inputPrimCount,
                             [&](uint64_t c) { return coneIndices(set, c); }, name, flat, record, report);
}

void flattenIsosurfaces(const IsosurfaceSet& set, UsedGeometry& g, FlatScene& flat, gpu::GeometryRecord& record,
                        SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    const glm::uvec3 d = set.dims, cells = d - 1u;
    const uint64_t isoCount = set.isovalues.size();
    if (set.mesh) {
        // A mesh cell (shared/scene.h IsoCellPrim): its box, the grid map and its leaf-order index.
        flat.isoMeshes.push_back({set.mesh, flat.isoCells.size(), p.blas.primOrder.size()});
        for (uint32_t slot : p.blas.primOrder) {
            const uint32_t prim = p.validPrims[slot];
            const uint64_t pair = p.isoCells[prim];
            const uint32_t cell = static_cast<uint32_t>(pair / isoCount), iso = static_cast<uint32_t>(pair % isoCount);
            const auto& [lo, hi] = set.mesh->cellBoxes[cell];
            gpu::IsoCellPrim c{};
            c.lowCorner = gpu::vec4(lo, set.isovalues[iso]);
            c.size = gpu::vec4(hi - lo, 0.0f);
            c.values0 = gpu::vec4(set.mesh->gridScale, glm::uintBitsToFloat(cell));
            c.values1 = gpu::vec4(set.mesh->lo, 0.0f);
            c.primId = prim;
            c.isovalueIndex = iso;
            flat.isoCells.push_back(c);
        }
    }
    auto at = [&](uint64_t x, uint64_t y, uint64_t z) { return set.values[(z * d.y + y) * d.x + x]; };
    for (uint32_t slot : set.mesh ? std::vector<uint32_t>{} : p.blas.primOrder) {
        const uint32_t prim = p.validPrims[slot];
        const uint64_t pair = p.isoCells[prim], cell = pair / isoCount;
        const uint32_t iso = static_cast<uint32_t>(pair % isoCount);
        const uint64_t x = cell % cells.x, y = (cell / cells.x) % cells.y, z = cell / (uint64_t(cells.x) * cells.y);
        gpu::IsoCellPrim c{};
        c.lowCorner = gpu::vec4(set.origin + glm::vec3(x, y, z) * set.spacing, set.isovalues[iso]);
        c.size = gpu::vec4(set.spacing, 0.0f);
        c.values0 = gpu::vec4(at(x, y, z), at(x + 1, y, z), at(x, y + 1, z), at(x + 1, y + 1, z));
        c.values1 = gpu::vec4(at(x, y, z + 1), at(x + 1, y, z + 1), at(x, y + 1, z + 1), at(x + 1, y + 1, z + 1));
        c.primId = prim;
        c.isovalueIndex = iso;
        flat.isoCells.push_back(c);
    }
    const std::string name = geometryLabel(g.kind, g.index);
    record.colorOffset = appendAttribute(set.colors, isoCount, "colors", name, flat, report);
    appendGeometryAttributes(set.attributes, 0, isoCount, {}, name, flat, record, report);
}

// Appends a geometry's BLAS, primitives, slot map and attributes; returns its GeometryRecord index.
uint32_t flattenGeometry(const SceneDescription& description, UsedGeometry& g, FlatScene& flat, SceneReport& report) {
    const PreparedGeometry& p = *g.prepared;
    g.nodeOffset = static_cast<uint32_t>(flat.nodes.size());
    switch (g.kind) {
    case GeometryKind::Triangles: g.primOffset = static_cast<uint32_t>(flat.triangles.size()); break;
    case GeometryKind::Spheres: g.primOffset = static_cast<uint32_t>(flat.spheres.size()); break;
    case GeometryKind::Cylinders: g.primOffset = static_cast<uint32_t>(flat.cylinders.size()); break;
    case GeometryKind::Cones: g.primOffset = static_cast<uint32_t>(flat.cones.size()); break;
    case GeometryKind::Isosurfaces: g.primOffset = static_cast<uint32_t>(flat.isoCells.size()); break;
    }
    flat.nodes.insert(flat.nodes.end(), p.blas4.nodes.begin(), p.blas4.nodes.end());
    gpu::GeometryRecord record{};
    record.kind = static_cast<uint32_t>(g.kind);
    record.slotOffset = static_cast<uint32_t>(flat.primSlots.size());
    record.indexOffset = record.normalOffset = record.colorOffset = record.texcoordOffset =
        record.primitiveColorOffset = gpu::NO_ATTRIBUTE;
    for (uint32_t& offset : record.attributeOffset) offset = gpu::NO_ATTRIBUTE;
    record.tangentOffset = gpu::NO_ATTRIBUTE;
    record.trianglesPerPrimitive = 1;
    flat.primSlots.resize(flat.primSlots.size() + p.inputPrimCount, ~0u);
    for (uint32_t slot = 0; slot < p.blas.primOrder.size(); ++slot)
        flat.primSlots[record.slotOffset + p.validPrims[p.blas.primOrder[slot]]] = g.primOffset + slot;
    switch (g.kind) {
    case GeometryKind::Triangles: flattenTriangles(description.meshes[g.index], g, flat, record, report); break;
    case GeometryKind::Spheres: flattenSpheres(description.sphereSets[g.index], g, flat, record, report); break;
    case GeometryKind::Cylinders: flattenCylinders(description.cylinderSets[g.index], g, flat, record, report); break;
    case GeometryKind::Cones: flattenCones(description.coneSets[g.index], g, flat, record, report); break;
    case GeometryKind::Isosurfaces: flattenIsosurfaces(description.isosurfaceSets[g.index], g, flat, record, report); break;
    }
    flat.geometries.push_back(record);
    return static_cast<uint32_t>(flat.geometries.size() - 1);
}

size_t geometryCount(const SceneDescription& d, GeometryKind kind) {
    switch (kind) {
    case GeometryKind::Triangles: return d.meshes.size();
    case GeometryKind::Spheres: return d.sphereSets.size();
    case GeometryKind::Cylinders: return d.cylinderSets.size();
    case GeometryKind::Cones: return d.coneSets.size();
    case GeometryKind::Isosurfaces: return d.isosurfaceSets.size();
    }
    return 0;
}

// Validates and builds one geometry, or takes it from `previous` when its identity is unchanged.
std::shared_ptr<const PreparedGeometry> prepareOrReuse(const SceneDescription& d, GeometryKind kind, uint32_t index,
                                                       const bvh::BuildOptions& options,
                                                       const std::vector<std::shared_ptr<const PreparedGeometry>>* previous,
                                                       SceneReport& report) {
    auto lookup = [&](const auto& geometry) -> std::shared_ptr<const PreparedGeometry> {
        if (previous && geometry.identity.key != 0)
            for (const auto& p : *previous)
                if (p->kind == kind && p->identity.key == geometry.identity.key &&
                    p->identity.version == geometry.identity.version && sameOptions(p->buildOptions, options) &&
                    fits(*p, geometry)) {
                    ++report.blasReused;
                    return p;
                }
        ++report.blasBuilt;
        return prepareGeometry(geometry, options);
    };
    switch (kind) {
    case GeometryKind::Triangles: return lookup(d.meshes[index]);
    case GeometryKind::Spheres: return lookup(d.sphereSets[index]);
    case GeometryKind::Cylinders: return lookup(d.cylinderSets[index]);
    case GeometryKind::Cones: return lookup(d.coneSets[index]);
    case GeometryKind::Isosurfaces: return lookup(d.isosurfaceSets[index]);
    }
    return nullptr;
}

}  // namespace

Scene::Scene(const vk::Context& context, const SceneDescription& description, const bvh::BuildOptions& buildOptions,
             const Scene* previous, Traversal traversal) {
    // 1. Validate every instance and every geometry it references (once per geometry); what cannot be
    //    traced is skipped and reported.
    std::vector<UsedGeometry> used;
    std::vector<int64_t> slots[5] = {std::vector<int64_t>(description.meshes.size(), -1),
                                     std::vector<int64_t>(description.sphereSets.size(), -1),
                                     std::vector<int64_t>(description.cylinderSets.size(), -1),
                                     std::vector<int64_t>(description.coneSets.size(), -1),
                                     std::vector<int64_t>(description.isosurfaceSets.size(), -1)};
    struct ValidInstance { uint32_t input; uint32_t geometry; };
    std::vector<ValidInstance> valid;
    auto skipInstance = [&](uint32_t i, const std::string& why) {
        report_.messages.push_back("instance " + std::to_string(i) + ": " + why + "; skipped");
        ++report_.instancesSkipped;
    };
    const auto start = Clock::now();
    for (uint32_t i = 0; i < description.instances.size(); ++i) {
        const InstanceDescription& inst = description.instances[i];
        const auto kindIndex = static_cast<uint32_t>(inst.geometry.kind);
        if (kindIndex > static_cast<uint32_t>(GeometryKind::Isosurfaces)) {
            skipInstance(i, "unknown geometry kind " + std::to_string(kindIndex));
            continue;
        }
        const std::string name = geometryLabel(inst.geometry.kind, inst.geometry.index);
        if (inst.geometry.index >= geometryCount(description, inst.geometry.kind)) {
            skipInstance(i, "references " + name + ", which does not exist");
            continue;
        }
        if (!affineAndInvertible(inst.transform)) {
            skipInstance(i, "transform is not finite, affine and invertible");
            continue;
        }
        int64_t& slot = slots[kindIndex][inst.geometry.index];
        if (slot < 0) {
            auto prepared = prepareOrReuse(description, inst.geometry.kind, inst.geometry.index, buildOptions,
                                           previous ? &previous->reusable_ : nullptr, report_);
            for (const std::string& problem : prepared->problems) report_.messages.push_back(name + ": " + problem);
            const uint64_t kept = prepared->validPrims.size();
            switch (inst.geometry.kind) {
            case GeometryKind::Triangles: report_.trianglesKept += kept; report_.trianglesSkipped += prepared->skipped; break;
            case GeometryKind::Spheres: report_.spheresKept += kept; report_.spheresSkipped += prepared->skipped; break;
            case GeometryKind::Cylinders: report_.cylindersKept += kept; report_.cylindersSkipped += prepared->skipped; break;
            case GeometryKind::Cones: report_.conesKept += kept; report_.conesSkipped += prepared->skipped; break;
            case GeometryKind::Isosurfaces: report_.isoCellsKept += kept; report_.isoCellsSkipped += prepared->skipped; break;
            }
            if (prepared->identity.key != 0) reusable_.push_back(prepared);
            slot = static_cast<int64_t>(used.size());
            used.push_back({inst.geometry.kind, inst.geometry.index, std::move(prepared)});
        }
        if (used[slot].prepared->validPrims.empty()) {
            skipInstance(i, name + " has no valid primitives");
            continue;
        }
        valid.push_back({i, static_cast<uint32_t>(slot)});
        // FEATURE_TRIANGLES.. FEATURE_CONES are bit GEOMETRY_*; iso-surfaces have a bit of their own.
        features_ |= inst.geometry.kind == GeometryKind::Isosurfaces ? gpu::FEATURE_ISOSURFACES : 1u << kindIndex;
        if (inst.geometry.kind == GeometryKind::Isosurfaces && description.isosurfaceSets[inst.geometry.index].mesh)
            features_ |= gpu::FEATURE_MESH_ISOSURFACES;
    }
    report_.instancesKept = valid.size();
    report_.blasBuildSeconds = secondsSince(start);

    // 2. The TLAS over the instances' world boxes.
    std::vector<bvh::Aabb> instanceBoxes;
    for (const auto& v : valid)
        instanceBoxes.push_back(transformBox(used[v.geometry].prepared->blas.bounds, description.instances[v.input].transform));
    const auto tlasStart = Clock::now();
    bvh::BuildOptions tlasOptions = buildOptions;
    tlasOptions.maxLeafSize = 1;  // the kernel enters one instance per TLAS leaf entry
    const bvh::Bvh tlas = bvh::buildBinnedSah(instanceBoxes, tlasOptions);
    report_.tlasBuildSeconds = secondsSince(tlasStart);
    bounds_ = tlas.bounds;
    VolumeTable volumes = buildVolumeTable(description.volumes);
    report_.volumesKept = volumes.records.size();
    report_.volumesSkipped = volumes.skipped;
    report_.messages.insert(report_.messages.end(), volumes.messages.begin(), volumes.messages.end());
    if (!volumes.records.empty()) {
        bounds_.extend(volumes.bounds);
        features_ |= gpu::FEATURE_VOLUMES;
        for (const gpu::VolumeRecord& r : volumes.records) {
            if (r.kind == gpu::VOLUME_KIND_UNSTRUCTURED) features_ |= gpu::FEATURE_UNSTRUCTURED_VOLUMES;
            if (r.kind == gpu::VOLUME_KIND_NANOVDB) features_ |= gpu::FEATURE_NANOVDB_VOLUMES;
            if (r.kind == gpu::VOLUME_KIND_AMR) features_ |= gpu::FEATURE_AMR_VOLUMES;
        }
    }
    std::vector<bvh::Aabb> occupied = instanceBoxes;
    occupied.insert(occupied.end(), volumes.boxes.begin(), volumes.boxes.end());
    regions_ = bvh::clusterBoxes(occupied, kMaxRegions);

    // 3. Flatten: TLAS nodes first, then each BLAS, every BVH collapsed to 4 wide (the kernels' layout);
    //    primitives in leaf order; shading data per geometry.
    FlatScene flat;
    flat.nodes = bvh::collapseToBvh4(tlas).nodes;
    std::vector<uint32_t> geometryRecord(used.size());
    for (size_t g = 0; g < used.size(); ++g)
        if (!used[g].prepared->validPrims.empty()) geometryRecord[g] = flattenGeometry(description, used[g], flat, report_);

    const float sceneRadius = description.lightSceneRadius > 0.0f ? description.lightSceneRadius
                              : bounds_.lo.x <= bounds_.hi.x ? 0.5f * glm::length(bounds_.hi - bounds_.lo) : 1.0f;
    lightSceneRadius_ = std::isfinite(sceneRadius) && sceneRadius > 0.0f ? sceneRadius : 1.0f;
    ShadingTables shading = buildShadingTables(description, lightSceneRadius_);
    report_.materialsRepaired = shading.materialsRepaired;
    report_.texturesSkipped = shading.texturesSkipped;
    report_.lightsKept = shading.lights.size();
    report_.lightsSkipped = shading.lightsSkipped;
    report_.messages.insert(report_.messages.end(), shading.messages.begin(), shading.messages.end());
    triangleLights_ = std::move(shading.localTriangleLights);

    std::vector<gpu::InstancePrim> instances;
    for (uint32_t slot : tlas.primOrder) {
        const ValidInstance& v = valid[slot];
        const UsedGeometry& g = used[v.geometry];
        gpu::InstancePrim prim{};
        const glm::dmat4 toWorld(description.instances[v.input].transform);
        storeRows(glm::inverse(toWorld), prim.worldToObject);
        storeRows(toWorld, prim.objectToWorld);
        prim.blasNodeOffset = g.nodeOffset;
        prim.primOffset = g.primOffset;
        prim.geometryKind = static_cast<uint32_t>(g.kind);
        prim.instanceId = v.input;
        instances.push_back(prim);
    }
    instanceCount_ = static_cast<uint32_t>(instances.size());
    traversal_ = resolveTraversal(context, traversal);
    const bool rayQuery = traversal_ == Traversal::RayQuery;

    std::vector<gpu::InstanceShading> instanceShading(description.instances.size(), gpu::InstanceShading{});
    uint64_t badMaterial = 0;
    for (const ValidInstance& v : valid) {
        const InstanceDescription& inst = description.instances[v.input];
        gpu::InstanceShading& s = instanceShading[v.input];
        const glm::dmat4 toWorld(inst.transform);
        storeRows(glm::inverse(toWorld), s.worldToObject);
        storeRows(toWorld, s.objectToWorld);
        s.geometry = geometryRecord[v.geometry];
        const bool materialValid = inst.materialIndex < description.materials.size();
        badMaterial += materialValid ? 0 : 1;
        s.material = materialValid ? inst.materialIndex : defaultMaterialIndex(description);
        s.objectId = inst.objectId;
        s.userInstanceId = inst.instanceId;
        s.attributeOffset = gpu::NO_ATTRIBUTE;
        s.attributeMask = 0;
        const std::optional<glm::vec4> uniforms[5] = {inst.color, inst.attributes[0], inst.attributes[1],
                                                      inst.attributes[2], inst.attributes[3]};
        for (uint32_t u = 0; u < 5; ++u) {
            if (!uniforms[u]) continue;
            if (s.attributeOffset == gpu::NO_ATTRIBUTE) {
                s.attributeOffset = static_cast<uint32_t>(flat.attributes.size());
                flat.attributes.resize(flat.attributes.size() + 5, gpu::vec4(0.0f, 0.0f, 0.0f, 1.0f));
            }
            if (glm::any(glm::isnan(*uniforms[u])) || glm::any(glm::isinf(*uniforms[u]))) {
                report_.messages.push_back("instance " + std::to_string(v.input) + ": a uniform attribute holds NaN or Inf; attribute ignored");
                ++report_.attributesIgnored;
                continue;
            }
            flat.attributes[s.attributeOffset + u] = toVec4(*uniforms[u]);
            s.attributeMask |= 1u << u;
        }
    }
    if (badMaterial)
        report_.messages.push_back(std::to_string(badMaterial) + " instance(s) name a material index beyond the " +
                                   std::to_string(description.materials.size()) + " material(s); the default matte is used");
    lightCount_ = static_cast<uint32_t>(shading.lights.size());
    lightPowerTotal_ = shading.lightPowerTotal;
    features_ |= shadingFeatures(description);  // materials and lights: see FeatureSet.h
    for (const gpu::LightRecord& light : shading.lights)  // also emissive triangles, this rank's and the others'
        features_ |= light.kind < 8 ? 1u << (gpu::FEATURE_LIGHT_SHIFT + light.kind) : gpu::FEATURE_LIGHTS;

    // 4. Upload. Empty arrays still get a (tiny) buffer so every address in SceneDesc is valid.
    auto upload = [&](vk::Buffer& buffer, const auto& items, const char* name, VkBufferUsageFlags usage = 0) {
        const VkDeviceSize bytes = items.size() * sizeof(items[0]);
        buffer = vk::Buffer(context, bytes, name, usage);
        buffer.upload(items.data(), bytes);
        report_.gpuBytes += bytes;
        return buffer.address();
    };
    gpu::SceneDesc desc{};
    desc.nodes = upload(nodes_, bvh::compressBvh4(flat.nodes), "scene BVH4 nodes");
    // Triangle BLASes read their vertices straight from this buffer (ray-query traversal).
    desc.triangles = upload(triangles_, flat.triangles, "scene triangles",
                            rayQuery ? VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR : 0);
    desc.spheres = upload(spheres_, flat.spheres, "scene spheres");
    desc.cylinders = upload(cylinders_, flat.cylinders, "scene cylinders");
    desc.cones = upload(cones_, flat.cones, "scene cones");
    // Unstructured meshes whose iso-surfaces are drawn: their words on the device, once per mesh.
    for (const FlatScene::IsoMesh& m : flat.isoMeshes) {
        const auto same = [&](const std::pair<std::shared_ptr<const UnstructuredGrid>, vk::Buffer>& kept) { return kept.first == m.mesh; };
        auto it = std::find_if(isoMeshes_.begin(), isoMeshes_.end(), same);
        if (it == isoMeshes_.end()) {
            const size_t bytes = m.mesh->words.size() * sizeof(uint32_t);
            isoMeshes_.emplace_back(m.mesh, vk::Buffer(context, bytes, "iso-surface mesh"));
            isoMeshes_.back().second.upload(m.mesh->words.data(), bytes);
            report_.gpuBytes += bytes;
            it = std::prev(isoMeshes_.end());
        }
        const uint64_t address = it->second.address();
        for (size_t i = m.first; i < m.first + m.count; ++i) {
            flat.isoCells[i].meshLow = uint32_t(address);
            flat.isoCells[i].meshHigh = uint32_t(address >> 32);
        }
    }
    desc.isoCells = upload(isoCells_, flat.isoCells, "scene iso-surface cells");
    desc.instances = upload(instances_, instances, "scene instances");
    desc.instanceShading = upload(instanceShading_, instanceShading, "scene instance shading");
    desc.geometries = upload(geometries_, flat.geometries, "scene geometry records");
    desc.primSlots = upload(primSlots_, flat.primSlots, "scene primitive slots");
    desc.vertexIndices = upload(vertexIndices_, flat.vertexIndices, "scene vertex indices");
    desc.attributes = upload(attributes_, flat.attributes, "scene attributes");
    desc.materials = upload(materials_, shading.materials, "scene materials");
    desc.textures = upload(textures_, shading.textures, "scene textures");
    desc.texels = upload(texels_, shading.texels, "scene texels");
    desc.lights = upload(lights_, shading.lights, "scene lights");
    // Each kept volume's voxels in a buffer of their own: taken from `previous` (or an earlier record of this
    // scene: one field in several volumes) when the voxel identity matches, else uploaded.
    for (size_t r = 0; r < volumes.records.size(); ++r) {
        const Volume& v = description.volumes[volumes.sources[r]];
        // The voxels, or an unstructured mesh's words (UnstructuredGrid.h), a NanoVDB grid's (NanoVdbGrid.h) or an
        // AMR hierarchy's (AmrGrid.h).
        const std::vector<uint32_t>* words = v.unstructured ? &v.unstructured->words
                                             : v.nanovdb    ? &v.nanovdb->words
                                             : v.amr        ? &v.amr->words
                                                            : nullptr;
        const void* fieldData = words ? static_cast<const void*>(words->data()) : v.values->data();
        const size_t fieldBytes = words ? words->size() * sizeof(uint32_t) : v.values->size() * sizeof(float);
        const auto same = [&](const std::shared_ptr<const VolumeVoxels>& kept) {
            return v.voxelIdentity.key != 0 && kept->identity.key == v.voxelIdentity.key &&
                   kept->identity.version == v.voxelIdentity.version && kept->bytes == fieldBytes;
        };
        std::shared_ptr<const VolumeVoxels> voxels;
        if (const auto it = std::find_if(volumeVoxels_.begin(), volumeVoxels_.end(), same); it != volumeVoxels_.end())
            voxels = *it;
        else if (previous)
            if (const auto at = std::find_if(previous->volumeVoxels_.begin(), previous->volumeVoxels_.end(), same);
                at != previous->volumeVoxels_.end())
                voxels = *at;
        if (voxels) {
            ++report_.volumeVoxelsReused;
        } else {
            auto made = std::make_shared<VolumeVoxels>();
            made->identity = v.voxelIdentity;
            made->bytes = fieldBytes;
            made->buffer = vk::Buffer(context, fieldBytes, "volume voxels");
            made->buffer.upload(fieldData, fieldBytes);
            voxels = std::move(made);
            ++report_.volumeVoxelsUploaded;
        }
        if (std::find(volumeVoxels_.begin(), volumeVoxels_.end(), voxels) == volumeVoxels_.end())
            report_.gpuBytes += voxels->buffer.size();
        volumes.records[r].voxels = voxels->buffer.address();
        volumeVoxels_.push_back(std::move(voxels));
    }
    desc.volumes = upload(volumes_, volumes.records, "scene volumes");
    desc.volumeData = upload(volumeData_, volumes.data, "scene volume data");
    desc.volumeCount = static_cast<uint32_t>(volumes.records.size());
    const MajorantGrids grids = buildMajorantsOnDevice(context, volumes_, volumeData_, volumes.records);
    report_.volumeMajorantSeconds = grids.seconds;
    report_.volumesCellByCell = grids.cellByCellVolumes;
    desc.instanceCount = instanceCount_;
    desc.lightCount = lightCount_;
    desc.materialCount = static_cast<uint32_t>(shading.materials.size());
    desc.textureCount = static_cast<uint32_t>(shading.textures.size());
    desc.lightPowerTotal = shading.lightPowerTotal;
    desc.testedLightCount = shading.testedLightCount;
    desc.bsdfTables = shading.bsdfTableOffset;
    desc.environmentLight = shading.environmentLight;
    // Near 0 ray origins move by a fixed fraction of this unit (offsetRayOrigin): a world smaller than one
    // unit would otherwise hide its own thin gaps and contact shadows inside that offset.
    float magnitude = description.worldMagnitude > 0.0f ? description.worldMagnitude : 1.0f;
    if (description.worldMagnitude == 0.0f && bounds_.lo.x <= bounds_.hi.x) {
        const glm::vec3 largest = glm::max(glm::abs(bounds_.lo), glm::abs(bounds_.hi));
        magnitude = std::max(largest.x, std::max(largest.y, largest.z));
    }
    desc.originUnit = std::isfinite(magnitude) ? std::clamp(magnitude, 1e-30f, 1.0f) : 1.0f;

    // 5. Ray-query traversal: acceleration structures over the uploaded primitives, in the same order.
    if (rayQuery) {
        std::vector<AccelerationGeometry> geometries;
        for (const UsedGeometry& g : used)
            geometries.push_back({g.prepared, g.kind, g.primOffset, static_cast<uint32_t>(g.prepared->validPrims.size())});
        std::vector<uint32_t> instanceGeometry;
        for (uint32_t slot : tlas.primOrder) instanceGeometry.push_back(valid[slot].geometry);
        const AccelerationInputs inputs{geometries, desc.triangles, flat.spheres, flat.cylinders, flat.cones, flat.isoCells, instances,
                                        instanceGeometry};
        accelerationStructures_ = std::make_unique<AccelerationStructures>(
            context, inputs, previous ? previous->accelerationStructures_.get() : nullptr);
        desc.accelerationStructure = accelerationStructures_->tlasAddress();
        report_.accelerationStructuresBuilt = accelerationStructures_->blasBuilt();
        report_.accelerationStructuresReused = accelerationStructures_->blasReused();
        report_.accelerationStructurePrimitives = accelerationStructures_->primitivesBuilt();
        report_.accelerationStructureSeconds = accelerationStructures_->buildSeconds();
        report_.accelerationStructureBytes = accelerationStructures_->bytes();
        report_.gpuBytes += report_.accelerationStructureBytes;
    }
    upload(desc_, std::vector<gpu::SceneDesc>{desc}, "scene descriptor");
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

float Scene::ambientLightChance(const glm::vec3& ambient) const {
    return core::ambientLightChance(ambient, lightSceneRadius_, lightPowerTotal_);
}

}  // namespace ripple::core
