// Splitting a glTF scene over ranks (see ScenePartition.h). The spatial split cuts the set of triangle
// centroids at the count-weighted median of its longest axis, giving each side a share of the ranks in
// proportion, until each region has one rank: every rank gets a compact region of similar size.
#include "apps/scene/ScenePartition.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace ripple::apps {

namespace {

struct TriangleRef {
    glm::vec3 centroid{0.0f};
    uint32_t instance = 0;
    uint32_t primitive = 0;  // within the instance's mesh
    uint32_t triangle = 0;
};

// Ranks [rankBegin, rankEnd) share `items`; returns in `mine` those that `rank` gets.
void splitKd(std::vector<TriangleRef>::iterator begin, std::vector<TriangleRef>::iterator end, uint32_t rankBegin,
             uint32_t rankEnd, uint32_t rank, std::vector<TriangleRef>& mine) {
    if (rankEnd - rankBegin == 1) {
        if (rank == rankBegin) mine.assign(begin, end);
        return;
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (auto it = begin; it != end; ++it) {
        lo = glm::min(lo, it->centroid);
        hi = glm::max(hi, it->centroid);
    }
    const glm::vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const uint32_t leftRanks = (rankEnd - rankBegin) / 2;
    const auto count = size_t(end - begin);
    const auto middle = begin + std::ptrdiff_t(count * leftRanks / (rankEnd - rankBegin));
    std::nth_element(begin, middle, end,
                     [axis](const TriangleRef& a, const TriangleRef& b) { return a.centroid[axis] < b.centroid[axis]; });
    if (rank < rankBegin + leftRanks) splitKd(begin, middle, rankBegin, rankBegin + leftRanks, rank, mine);
    else splitKd(middle, end, rankBegin + leftRanks, rankEnd, rank, mine);
}

// A copy of `scene` without its instances, meshes and geometries (filled in by the partitions).
GltfScene emptyCopy(const GltfScene& scene) {
    GltfScene part;
    part.file = scene.file;
    part.materials = scene.materials;
    part.textures = scene.textures;
    part.images = scene.images;
    part.cameras = scene.cameras;
    part.lights = scene.lights;
    part.warnings = scene.warnings;
    part.boundsMin = scene.boundsMin;
    part.boundsMax = scene.boundsMax;
    return part;
}

GltfScene roundRobin(const GltfScene& whole, uint32_t rank, uint32_t ranks) {
    GltfScene part = emptyCopy(whole);
    std::unordered_map<uint32_t, uint32_t> meshIndex, geometryIndex;  // whole's index -> part's
    for (size_t i = rank; i < whole.instances.size(); i += ranks) {
        GltfMeshInstance instance = whole.instances[i];
        auto [mesh, addedMesh] = meshIndex.try_emplace(instance.mesh, uint32_t(part.meshes.size()));
        if (addedMesh) {
            GltfMesh copy = whole.meshes[instance.mesh];
            for (GltfPrimitive& primitive : copy.primitives) {
                auto [geometry, addedGeometry] = geometryIndex.try_emplace(primitive.geometry, uint32_t(part.geometries.size()));
                if (addedGeometry) part.geometries.push_back(whole.geometries[primitive.geometry]);
                primitive.geometry = geometry->second;
            }
            part.meshes.push_back(std::move(copy));
        }
        instance.mesh = mesh->second;
        part.instances.push_back(instance);
    }
    return part;
}

// The triangles of one geometry listed in `triangles`, with only the vertices they use.
GltfGeometry subset(const GltfGeometry& source, const std::vector<uint32_t>& triangles) {
    GltfGeometry out;
    std::unordered_map<uint32_t, uint32_t> vertexIndex;
    auto vertex = [&](uint32_t v) {
        auto [it, added] = vertexIndex.try_emplace(v, uint32_t(out.positions.size()));
        if (added) {
            out.positions.push_back(source.positions[v]);
            if (!source.normals.empty()) out.normals.push_back(source.normals[v]);
            if (!source.texcoords.empty()) out.texcoords.push_back(source.texcoords[v]);
            if (!source.colors.empty()) out.colors.push_back(source.colors[v]);
        }
        return it->second;
    };
    for (uint32_t t : triangles) {
        const glm::uvec3& tri = source.indices[t];
        out.indices.push_back({vertex(tri.x), vertex(tri.y), vertex(tri.z)});
    }
    return out;
}

GltfScene spatial(const GltfScene& whole, uint32_t rank, uint32_t ranks) {
    std::vector<TriangleRef> all;
    all.reserve(whole.trianglesDrawn());
    for (uint32_t i = 0; i < whole.instances.size(); ++i) {
        const GltfMeshInstance& instance = whole.instances[i];
        const GltfMesh& mesh = whole.meshes[instance.mesh];
        for (uint32_t p = 0; p < mesh.primitives.size(); ++p) {
            const GltfGeometry& g = whole.geometries[mesh.primitives[p].geometry];
            for (uint32_t t = 0; t < g.indices.size(); ++t) {
                const glm::uvec3& tri = g.indices[t];
                const glm::vec3 local = (g.positions[tri.x] + g.positions[tri.y] + g.positions[tri.z]) / 3.0f;
                all.push_back({glm::vec3(instance.transform * glm::vec4(local, 1.0f)), i, p, t});
            }
        }
    }
    std::vector<TriangleRef> mine;
    splitKd(all.begin(), all.end(), 0, ranks, rank, mine);
    all = {};
    // Group this rank's triangles by instance and primitive, in the file's order.
    std::sort(mine.begin(), mine.end(), [](const TriangleRef& a, const TriangleRef& b) {
        return a.instance != b.instance ? a.instance < b.instance
               : a.primitive != b.primitive ? a.primitive < b.primitive : a.triangle < b.triangle;
    });
    GltfScene part = emptyCopy(whole);
    for (size_t k = 0; k < mine.size();) {
        const uint32_t instanceIndex = mine[k].instance;
        const GltfMeshInstance& source = whole.instances[instanceIndex];
        GltfMesh mesh;
        mesh.name = whole.meshes[source.mesh].name;
        while (k < mine.size() && mine[k].instance == instanceIndex) {
            const uint32_t primitive = mine[k].primitive;
            std::vector<uint32_t> triangles;
            for (; k < mine.size() && mine[k].instance == instanceIndex && mine[k].primitive == primitive; ++k)
                triangles.push_back(mine[k].triangle);
            const GltfPrimitive& original = whole.meshes[source.mesh].primitives[primitive];
            part.geometries.push_back(subset(whole.geometries[original.geometry], triangles));
            mesh.primitives.push_back({uint32_t(part.geometries.size() - 1), original.material});
        }
        part.meshes.push_back(std::move(mesh));
        part.instances.push_back({uint32_t(part.meshes.size() - 1), source.node, source.transform});
    }
    return part;
}

}  // namespace

PartitionKind parsePartitionKind(const std::string& name) {
    if (name == "round-robin") return PartitionKind::RoundRobin;
    if (name == "spatial") return PartitionKind::Spatial;
    throw std::invalid_argument("--partition '" + name + "': use round-robin or spatial");
}

GltfScene partitionScene(const GltfScene& whole, uint32_t rank, uint32_t ranks, PartitionKind kind) {
    if (ranks <= 1) return whole;
    if (rank >= ranks) throw std::invalid_argument("rank " + std::to_string(rank) + " of " + std::to_string(ranks));
    return kind == PartitionKind::RoundRobin ? roundRobin(whole, rank, ranks) : spatial(whole, rank, ranks);
}

}  // namespace ripple::apps
