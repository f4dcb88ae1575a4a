// The speed levers of ripple-bench (issue 2): the BVH2 -> BVH4 collapse, the single-level BVH4 kernels
// against the renderer's two-level kernels, subgroup packet traversal, and Morton ray ordering.
#include "bench/kernels/Bvh4TraceKernels.h"
#include "bench/kernels/RayOrder.h"
#include "core/bvh/Bvh4Compress.h"
#include "core/render/TraceKernels.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

using namespace ripple;
using ripple::test::testContext;

namespace {

std::vector<bvh::Aabb> triangleBoxes(const core::TriangleMesh& mesh) {
    std::vector<bvh::Aabb> boxes(mesh.positions.size() / 3);
    for (size_t t = 0; t < boxes.size(); ++t)
        for (int c = 0; c < 3; ++c) boxes[t].extend(mesh.positions[3 * t + c]);
    return boxes;
}

bvh::Aabb childBox(const gpu::Bvh4Node& n, int i) {
    return {{n.minX[i], n.minY[i], n.minZ[i]}, {n.maxX[i], n.maxY[i], n.maxZ[i]}};
}

bool contains(const bvh::Aabb& outer, const bvh::Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

// Walks a BVH4 checking the node contract of shaders/shared/bvh4.h; counts how often each leaf slot is
// reached and returns the union of the primitive boxes under `node`.
struct Bvh4Walk {
    const bvh::Bvh4& tree;
    const bvh::Bvh& bvh2;
    std::span<const bvh::Aabb> primBoxes;
    std::vector<uint32_t> slotVisits;
    uint32_t badBoxes = 0, underfullWithInner = 0, nodesSeen = 0;

    bvh::Aabb walk(uint32_t node) {
        REQUIRE(node < tree.nodes.size());
        ++nodesSeen;
        const gpu::Bvh4Node& n = tree.nodes[node];
        bvh::Aabb all;
        uint32_t used = 0;
        bool hasInner = false;
        for (int i = 0; i < 4; ++i) {
            const uint32_t word = n.children[i];
            if (word == gpu::BVH4_EMPTY_CHILD) continue;
            ++used;
            const bvh::Aabb box = childBox(n, i);
            bvh::Aabb subtree;
            if (word & gpu::BVH4_LEAF_BIT) {
                const uint32_t first = (word >> 3) & gpu::BVH4_MAX_LEAF_FIRST, count = (word & 7u) + 1;
                for (uint32_t s = first; s < first + count; ++s) {
                    REQUIRE(s < slotVisits.size());
                    ++slotVisits[s];
                    subtree.extend(primBoxes[bvh2.primOrder[s]]);
                }
            } else {
                hasInner = true;
                subtree = walk(word);
            }
            badBoxes += !contains(box, subtree);
            all.extend(subtree);
        }
        underfullWithInner += used < 4 && hasInner;
        return all;
    }
};

void checkCollapse(const std::vector<bvh::Aabb>& boxes, uint32_t maxChildren) {
    const bvh::Bvh bvh2 = bvh::buildBinnedSah(boxes);
    const bvh::Bvh4 tree = bvh::collapseToBvh4(bvh2, maxChildren);
    Bvh4Walk w{tree, bvh2, boxes, std::vector<uint32_t>(boxes.size(), 0)};
    w.walk(0);
    // Every primitive exactly once, every box holding its subtree, every node reached once.
    CHECK(std::all_of(w.slotVisits.begin(), w.slotVisits.end(), [](uint32_t v) { return v == 1; }));
    CHECK(w.badBoxes == 0);
    CHECK(w.nodesSeen == tree.nodes.size());
    CHECK(tree.leafCount == bvh2.leafCount);
    CHECK(tree.depth <= bvh2.depth + 1);  // leaves count as a level here; the BVH2's depth counts nodes
    if (maxChildren == 4) CHECK(w.underfullWithInner == 0);  // greedy: stops only when just leaves are left
    if (maxChildren == 2) CHECK(tree.nodes.size() == bvh2.nodes.size());
}

// Exact equality: both kernels run the same triangle and box tests on the same leaves in float, so only
// the visiting order differs, and that changes nothing unless two triangles tie at the same t (a
// random soup with random rays has none; the count is printed if it ever happens).
void checkSameHits(std::span<const gpu::Hit> expected, std::span<const gpu::Hit> actual, const char* what) {
    REQUIRE(expected.size() == actual.size());
    size_t differ = 0, hits = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        const gpu::Hit& a = expected[i];
        const gpu::Hit& b = actual[i];
        hits += a.status == gpu::HIT_FOUND;
        differ += a.status != b.status ||
                  (a.status == gpu::HIT_FOUND && (a.primId != b.primId || a.t != b.t || a.u != b.u || a.v != b.v));
    }
    CHECK_MESSAGE(differ == 0, what << ": " << differ << " of " << expected.size() << " rays differ");
    CHECK(hits > expected.size() / 4);  // the rays must mostly hit, or the comparison proves little
}

}  // namespace

TEST_CASE("BVH4 collapse keeps every primitive once and every child box holds its subtree") {
    for (uint32_t count : {1u, 2u, 3u, 9u, 5000u}) {
        CAPTURE(count);
        const auto boxes = triangleBoxes(test::randomTriangleSoup(count, 40 + count));
        for (uint32_t maxChildren : {2u, 4u}) {
            CAPTURE(maxChildren);
            checkCollapse(boxes, maxChildren);
        }
    }
    CHECK(bvh::collapseToBvh4(bvh::Bvh{}).nodes.empty());
    CHECK_THROWS_WITH_AS(bvh::collapseToBvh4(bvh::buildBinnedSah(triangleBoxes(test::randomTriangleSoup(4, 1))), 5),
                         doctest::Contains("maxChildren"), std::invalid_argument);
}

// The renderer's traversal uses the all-ones word (an empty slot) as its return-to-TLAS entry, so no leaf
// word may equal it: a leaf's last slot must fit the 28 bits.
TEST_CASE("BVH4 leaf words: the last addressable slot, never the empty-slot word") {
    auto oneLeaf = [](uint32_t first, uint32_t count) {
        bvh::Bvh bvh2;
        gpu::BvhNode root{};
        root.leftMin = gpu::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(first));
        root.leftMax = gpu::vec4(1.0f, 1.0f, 1.0f, std::bit_cast<float>(count));
        bvh2.nodes.push_back(root);  // right child: count 0, reference 0, i.e. empty
        return bvh2;
    };
    const bvh::Bvh4 last = bvh::collapseToBvh4(oneLeaf(gpu::BVH4_MAX_LEAF_FIRST, 1));
    REQUIRE(last.nodes.size() == 1);
    CHECK(last.nodes[0].children.x == 0xFFFFFFF8u);
    CHECK(last.nodes[0].children.y == gpu::BVH4_EMPTY_CHILD);
    CHECK(bvh::collapseToBvh4(oneLeaf(gpu::BVH4_MAX_LEAF_FIRST - 7, 8)).nodes[0].children.x == 0xFFFFFFC7u);
    CHECK_THROWS_WITH_AS(bvh::collapseToBvh4(oneLeaf(gpu::BVH4_MAX_LEAF_FIRST, 2)), doctest::Contains("last slot"),
                         std::invalid_argument);
}

TEST_CASE("compressed BVH4 child boxes hold the full ones, within one quantization step") {
    // Off the origin, so the rounding of frame + q * scale matters.
    core::TriangleMesh mesh = test::randomTriangleSoup(4000, 31, 0.5f);
    for (glm::vec3& p : mesh.positions) p += glm::vec3(300.0f, -70.0f, 5.0f);
    const bvh::Bvh4 tree = bvh::collapseToBvh4(bvh::buildBinnedSah(triangleBoxes(mesh)));
    const auto compressed = bvh::compressBvh4(tree);
    REQUIRE(compressed.size() == tree.nodes.size());
    size_t notContained = 0, loose = 0, children = 0;
    for (size_t n = 0; n < tree.nodes.size(); ++n) {
        const gpu::Bvh4Node& full = tree.nodes[n];
        CHECK(compressed[n].children == full.children);
        bvh::Aabb frame;
        for (int i = 0; i < 4; ++i)
            if (full.children[i] != gpu::BVH4_EMPTY_CHILD)
                frame.extend(childBox(full, i));
        for (int i = 0; i < 4; ++i) {
            if (full.children[i] == gpu::BVH4_EMPTY_CHILD) continue;
            ++children;
            const bvh::Aabb exact = childBox(full, i);
            const bvh::Aabb q = bvh::dequantizedBox(compressed[n], i);
            notContained += !contains(q, exact);
            // Conservative but useful: each bound within two steps (scale < 2 * extent / 255, rounding down
            // of lo and up of hi adds at most one) plus two ulps at 512 (the sum's rounding).
            const float ulp512 = std::nextafter(512.0f, 1e9f) - 512.0f;
            const glm::vec3 slack = (frame.hi - frame.lo) * (4.0f / 255.0f) + 2.0f * ulp512;
            loose += glm::any(glm::greaterThan(exact.lo - q.lo, slack)) ||
                     glm::any(glm::greaterThan(q.hi - exact.hi, slack));
        }
    }
    CHECK(children > tree.nodes.size() * 2);
    CHECK(notContained == 0);
    CHECK(loose == 0);
}

TEST_CASE("BVH4 and single-level BVH2 kernels give the renderer's hits on random rays") {
    test::ValidationGuard guard;
    const core::TriangleMesh mesh = test::randomTriangleSoup(3000, 7);
    const core::SceneDescription description = test::sceneOf(mesh);
    std::vector<gpu::Ray> rays = test::raysTowardPoints(description, 4096, 8);
    const auto random = test::randomRays(2048, 9, glm::vec3(-1), glm::vec3(1));
    rays.insert(rays.end(), random.begin(), random.end());

    core::Scene scene(testContext(), description);
    core::TraceKernels bvh2Kernels(testContext(), {.traversal = core::Traversal::Software});
    const auto expectedClosest = bvh2Kernels.traceClosest(scene, rays);
    const auto expectedAny = bvh2Kernels.traceAny(scene, rays);

    bvh::Bvh4TraceKernels kernels(testContext());
    for (uint32_t width : {4u, 2u}) {
        for (bool compressed : {false, true}) {
            CAPTURE(width);
            CAPTURE(compressed);
            const bvh::Bvh4Mesh wide(testContext(), mesh, {.maxChildren = width, .compressed = compressed});
            checkSameHits(expectedClosest, kernels.traceClosest(wide, rays), width == 4 ? "BVH4" : "single-level BVH2");
            CHECK(kernels.traceAny(wide, rays) == expectedAny);
        }
    }

    const bvh::Bvh4Mesh empty(testContext(), core::TriangleMesh{});
    for (const gpu::Hit& h : kernels.traceClosest(empty, std::span(rays).first(64))) CHECK(h.status == gpu::HIT_MISS);
}

TEST_CASE("BVH4 traversal that spends its step budget is flagged, never wrong") {
    test::ValidationGuard guard;
    const core::TriangleMesh mesh = test::randomTriangleSoup(3000, 11);
    const auto rays = test::raysTowardPoints(test::sceneOf(mesh), 2048, 12);
    const bvh::Bvh4Mesh wide(testContext(), mesh, {});
    const auto full = bvh::Bvh4TraceKernels(testContext()).traceClosest(wide, rays);
    // 12 steps reach a leaf of this ~6-level tree for some rays and not for others.
    const auto cut = bvh::Bvh4TraceKernels(testContext(), 64, 12).traceClosest(wide, rays);
    size_t flagged = 0, wrong = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (cut[i].status & gpu::HIT_FLAG_RAN_OUT) { ++flagged; continue; }
        wrong += cut[i].status != full[i].status || cut[i].primId != full[i].primId || cut[i].t != full[i].t;
    }
    CHECK(wrong == 0);
    CHECK(flagged > 0);
    CHECK(flagged < rays.size());
    CHECK_THROWS_AS(bvh::Bvh4TraceKernels(testContext(), 64, core::kMaxStepBudget + 1), std::invalid_argument);

    core::TriangleMesh bad = test::randomTriangleSoup(10, 13);
    bad.positions[4].y = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH_AS(bvh::Bvh4Mesh(testContext(), bad), doctest::Contains("vertex 4 of triangle 1 is NaN"),
                         std::invalid_argument);
}

TEST_CASE("BVH4 subgroup packet traversal gives the per-lane traversal's hits on random rays") {
    test::ValidationGuard guard;
    const core::TriangleMesh mesh = test::randomTriangleSoup(3000, 21);
    // Coherent rays toward the mesh, incoherent random ones, and a count that ends in a partial subgroup
    // and workgroup (the lanes past the end must ride along without writing).
    std::vector<gpu::Ray> rays = test::raysTowardPoints(test::sceneOf(mesh), 4096, 22);
    const auto random = test::randomRays(2048 + 37, 23, glm::vec3(-1), glm::vec3(1));
    rays.insert(rays.end(), random.begin(), random.end());

    bvh::Bvh4TraceKernels lanes(testContext());
    bvh::Bvh4TraceKernels packet(testContext(), 64, 30000, bvh::Bvh4Traversal::Packet);
    for (uint32_t width : {4u, 2u}) {
        for (bool compressed : {false, true}) {
            CAPTURE(width);
            CAPTURE(compressed);
            const bvh::Bvh4Mesh wide(testContext(), mesh, {.maxChildren = width, .compressed = compressed});
            const auto expectedClosest = lanes.traceClosest(wide, rays);
            const auto expectedAny = lanes.traceAny(wide, rays);
            checkSameHits(expectedClosest, packet.traceClosest(wide, rays), "packet traversal");
            const auto occluded = packet.traceAny(wide, rays);
            CHECK(occluded == expectedAny);
            CHECK(std::count(occluded.begin(), occluded.end(), gpu::HIT_FOUND) > std::ptrdiff_t(rays.size() / 4));
        }
    }
    const bvh::Bvh4Mesh empty(testContext(), core::TriangleMesh{});
    for (const gpu::Hit& h : packet.traceClosest(empty, std::span(rays).first(13))) CHECK(h.status == gpu::HIT_MISS);
}

TEST_CASE("BVH4 packet traversal that spends its step budget is flagged, never wrong") {
    test::ValidationGuard guard;
    const core::TriangleMesh mesh = test::randomTriangleSoup(3000, 11);
    const auto rays = test::raysTowardPoints(test::sceneOf(mesh), 2048, 12);
    const bvh::Bvh4Mesh wide(testContext(), mesh, {});
    const auto full = bvh::Bvh4TraceKernels(testContext()).traceClosest(wide, rays);
    // The budget counts the packet's steps, the union of its rays' paths, so how many steps a ray needs
    // depends on the subgroup size: a sweep of budgets must flag fewer rays as it grows, every ray at 20,
    // none at 30000 (the full run above), and some but not all at one budget between.
    size_t previous = rays.size();
    bool someButNotAll = false;
    for (uint32_t budget : {20u, 60u, 120u, 240u, 480u}) {
        CAPTURE(budget);
        const auto cut =
            bvh::Bvh4TraceKernels(testContext(), 64, budget, bvh::Bvh4Traversal::Packet).traceClosest(wide, rays);
        size_t flagged = 0, wrong = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            if (cut[i].status & gpu::HIT_FLAG_RAN_OUT) { ++flagged; continue; }
            wrong += cut[i].status != full[i].status || cut[i].primId != full[i].primId || cut[i].t != full[i].t;
        }
        CHECK(wrong == 0);
        CHECK(flagged <= previous);
        if (budget == 20u) CHECK(flagged == rays.size());
        CHECK(flagged % 4 == 0);  // a closest-hit packet that runs out flags all its lanes (4 | any subgroup size)
        someButNotAll |= flagged > 0 && flagged < rays.size();
        previous = flagged;
    }
    CHECK(someButNotAll);
    const auto packetFull =
        bvh::Bvh4TraceKernels(testContext(), 64, 30000, bvh::Bvh4Traversal::Packet).traceClosest(wide, rays);
    CHECK(std::none_of(packetFull.begin(), packetFull.end(),
                       [](const gpu::Hit& h) { return (h.status & gpu::HIT_FLAG_RAN_OUT) != 0; }));
    // 6 lanes fill no subgroup of 4 or more exactly.
    CHECK_THROWS_WITH_AS(bvh::Bvh4TraceKernels(testContext(), 6, 30000, bvh::Bvh4Traversal::Packet),
                         doctest::Contains("packet traversal needs"), std::invalid_argument);
}

TEST_CASE("Morton ray order is a permutation that sorts the keys, and results map back") {
    std::vector<gpu::Ray> rays = test::randomRays(20000, 21, glm::vec3(-3), glm::vec3(5));
    // A pinhole camera's rays share one origin; a NaN ray must still get a place.
    for (int i = 0; i < 100; ++i) rays.push_back({gpu::vec4(0.5f, 0.5f, 0.5f, 0.0f), rays[i].direction});
    rays.push_back({gpu::vec4(std::numeric_limits<float>::quiet_NaN(), 0, 0, 0), gpu::vec4(1, 0, 0, 1)});

    const std::vector<uint32_t> order = bvh::mortonRayOrder(rays);
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<uint32_t> identity(rays.size());
    std::iota(identity.begin(), identity.end(), 0u);
    CHECK(sorted == identity);

    bvh::Aabb bounds;
    for (const gpu::Ray& r : rays)
        if (std::isfinite(r.origin.x)) bounds.extend(glm::vec3(r.origin));
    size_t unsorted = 0;
    for (size_t i = 1; i < order.size(); ++i) {
        const uint64_t a = bvh::mortonRayKey(rays[order[i - 1]], bounds), b = bvh::mortonRayKey(rays[order[i]], bounds);
        unsorted += a > b || (a == b && order[i - 1] > order[i]);
    }
    CHECK(unsorted == 0);
    CHECK(order.back() == rays.size() - 1);  // the NaN ray sorts last

    std::vector<uint32_t> ids(rays.size());
    std::iota(ids.begin(), ids.end(), 100u);
    const auto traced = bvh::gatherInOrder(std::span<const uint32_t>(ids), order);
    CHECK(bvh::scatterFromOrder(std::span<const uint32_t>(traced), order) == ids);
}
