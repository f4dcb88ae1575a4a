// ripple-render's scene partition (apps/scene/ScenePartition.h): every drawn triangle lands on exactly one
// rank, in the same world-space place, and no rank holds the whole scene.
#include "apps/scene/ScenePartition.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <tuple>
#include <vector>

using namespace ripple::apps;

namespace {

// 6 instances of 2 meshes (one shared by 4 nodes), 2 x 8 x 8 triangles each, spread along x and y.
GltfScene gridScene() {
    GltfScene scene;
    for (int g = 0; g < 2; ++g) {
        GltfGeometry geometry;
        for (int y = 0; y <= 8; ++y)
            for (int x = 0; x <= 8; ++x) geometry.positions.push_back({float(x), float(y), float(g)});
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                const uint32_t a = y * 9 + x;
                geometry.indices.push_back({a, a + 1, a + 10});
                geometry.indices.push_back({a, a + 10, a + 9});
            }
        scene.geometries.push_back(geometry);
        scene.meshes.push_back({"mesh", {{uint32_t(g), -1}}});
    }
    for (uint32_t i = 0; i < 6; ++i) {
        GltfMeshInstance instance;
        instance.mesh = i < 4 ? 0 : 1;
        instance.node = i;
        instance.transform[3] = glm::vec4(10.0f * float(i % 3), 10.0f * float(i / 3), 0.0f, 1.0f);
        scene.instances.push_back(instance);
    }
    scene.lights.push_back(GltfLight{});
    return scene;
}

using Centroid = std::array<float, 3>;

std::vector<Centroid> centroids(const GltfScene& scene) {
    std::vector<Centroid> out;
    for (const GltfMeshInstance& instance : scene.instances)
        for (const GltfPrimitive& primitive : scene.meshes[instance.mesh].primitives) {
            const GltfGeometry& g = scene.geometries[primitive.geometry];
            for (const glm::uvec3& t : g.indices) {
                const glm::vec3 local = (g.positions[t.x] + g.positions[t.y] + g.positions[t.z]) / 3.0f;
                const glm::vec3 c = glm::vec3(instance.transform * glm::vec4(local, 1.0f));
                out.push_back({c.x, c.y, c.z});
            }
        }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("scene partition: each triangle on exactly one rank, none holding everything") {
    const GltfScene whole = gridScene();
    const std::vector<Centroid> all = centroids(whole);
    REQUIRE(all.size() == 6 * 128);
    for (PartitionKind kind : {PartitionKind::RoundRobin, PartitionKind::Spatial})
        for (uint32_t ranks : {2u, 3u, 4u}) {
            CAPTURE(int(kind));
            CAPTURE(ranks);
            std::vector<Centroid> joined;
            for (uint32_t rank = 0; rank < ranks; ++rank) {
                const GltfScene part = partitionScene(whole, rank, ranks, kind);
                const std::vector<Centroid> mine = centroids(part);
                CHECK(!mine.empty());
                CHECK(mine.size() < all.size());
                CHECK(part.lights.size() == 1);  // lights stay everywhere; ripple-render makes them on rank 0
                joined.insert(joined.end(), mine.begin(), mine.end());
            }
            std::sort(joined.begin(), joined.end());
            CHECK(joined == all);  // exact: partitions copy positions and transforms unchanged
        }
    // Round robin keeps instancing: a rank stores each mesh it draws once.
    CHECK(partitionScene(whole, 0, 2, PartitionKind::RoundRobin).geometries.size() == 2);
    CHECK(partitionScene(whole, 0, 2, PartitionKind::Spatial).geometries.size() >= 2);
    CHECK_THROWS_AS(parsePartitionKind("diagonal"), std::invalid_argument);
}

// The spatial partition is a k-d split balanced by count: each rank holds an equal share of the triangles
// (to one), and any two ranks' triangles lie on either side of some axis-aligned plane (the split where
// their regions part). Round robin over these instances is not separable so, which this tells apart.
TEST_CASE("scene partition: spatial regions are balanced and separated by planes") {
    const GltfScene whole = gridScene();
    const size_t total = centroids(whole).size();
    const auto separated = [](const std::vector<Centroid>& a, const std::vector<Centroid>& b) {
        for (int axis = 0; axis < 3; ++axis) {
            const auto byAxis = [axis](const Centroid& p, const Centroid& q) { return p[size_t(axis)] < q[size_t(axis)]; };
            const float aLo = (*std::min_element(a.begin(), a.end(), byAxis))[size_t(axis)];
            const float aHi = (*std::max_element(a.begin(), a.end(), byAxis))[size_t(axis)];
            const float bLo = (*std::min_element(b.begin(), b.end(), byAxis))[size_t(axis)];
            const float bHi = (*std::max_element(b.begin(), b.end(), byAxis))[size_t(axis)];
            if (aHi <= bLo || bHi <= aLo) return true;
        }
        return false;
    };
    for (uint32_t ranks : {2u, 3u, 4u}) {
        CAPTURE(ranks);
        std::vector<std::vector<Centroid>> parts;
        for (uint32_t rank = 0; rank < ranks; ++rank) {
            parts.push_back(centroids(partitionScene(whole, rank, ranks, PartitionKind::Spatial)));
            CHECK(parts.back().size() >= total / ranks);
            CHECK(parts.back().size() <= total / ranks + 1);
        }
        for (uint32_t a = 0; a < ranks; ++a)
            for (uint32_t b = a + 1; b < ranks; ++b) {
                CAPTURE(a);
                CAPTURE(b);
                CHECK(separated(parts[a], parts[b]));
            }
    }
    CHECK_FALSE(separated(centroids(partitionScene(whole, 0, 2, PartitionKind::RoundRobin)),
                          centroids(partitionScene(whole, 1, 2, PartitionKind::RoundRobin))));
}
