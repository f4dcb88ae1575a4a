// Structural checks of the binned SAH builder: every output is walked and validated against the node
// contract of shaders/shared/bvh.h, on random, degenerate and adversarial inputs.
#include "core/bvh/BinnedSahBuilder.h"

#include <doctest/doctest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace ripple::bvh {
namespace {

struct Child {
    Aabb box;
    uint32_t reference = 0;
    uint32_t count = 0;
    bool empty() const { return count == 0 && reference == 0; }
    bool leaf() const { return count > 0; }
};

Child child(const gpu::BvhNode& node, int side) {
    const glm::vec4 mn = side == 0 ? node.leftMin : node.rightMin;
    const glm::vec4 mx = side == 0 ? node.leftMax : node.rightMax;
    return {Aabb{glm::vec3(mn), glm::vec3(mx)}, std::bit_cast<uint32_t>(mn.w), std::bit_cast<uint32_t>(mx.w)};
}

bool sameBox(const Aabb& a, const Aabb& b) { return a.lo == b.lo && a.hi == b.hi; }

bool contains(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

struct TreeStats {
    uint32_t depth = 0;      // deepest leaf, root node = 1
    uint32_t leafCount = 0;
    double sahCost = 0.0;    // relative to one primitive test, traversal cost 1
};

// Walks the whole tree, CHECKing the layout contract, and returns what it measured.
TreeStats checkBvh(const Bvh& bvh, const std::vector<Aabb>& prims, const BuildOptions& options = {}) {
    TreeStats stats;
    const auto count = uint32_t(prims.size());
    REQUIRE(bvh.primOrder.size() == count);
    if (count == 0) {
        CHECK(bvh.nodes.empty());
        CHECK(bvh.depth == 0);
        CHECK(bvh.leafCount == 0);
        return stats;
    }
    REQUIRE(!bvh.nodes.empty());

    std::vector<uint32_t> seen(count, 0);
    for (uint32_t p : bvh.primOrder) {
        if (p >= count) FAIL("primOrder holds " << p << " of " << count << " primitives");
        ++seen[p];
    }
    CHECK(std::all_of(seen.begin(), seen.end(), [](uint32_t s) { return s == 1; }));

    Aabb all;
    for (const Aabb& b : prims) all.extend(b);
    CHECK(sameBox(bvh.bounds, all));

    const double rootArea = std::max(all.halfArea(), 1e-30f);
    std::vector<uint32_t> references(bvh.nodes.size(), 0);
    std::vector<uint32_t> slotCovered(count, 0);
    struct Item {
        uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 1}};
    Aabb rootBox;
    // Per-child properties are tallied and checked once, to keep the assertion count readable.
    uint32_t oversizedLeaves = 0, looseBoxes = 0;
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const gpu::BvhNode& node = bvh.nodes[item.node];
        for (int side = 0; side < 2; ++side) {
            const Child c = child(node, side);
            if (item.node == 0) rootBox.extend(c.box);
            if (c.empty()) {
                // Only the right child of a root whose left child is the only leaf may be empty.
                CHECK(item.node == 0);
                CHECK(side == 1);
                CHECK(child(node, 0).leaf());
                CHECK(c.box.lo == glm::vec3(FLT_MAX));
                CHECK(c.box.hi == glm::vec3(-FLT_MAX));
                continue;
            }
            stats.sahCost += c.box.halfArea() / rootArea * (c.leaf() ? double(c.count) : 1.0);
            if (c.leaf()) {
                oversizedLeaves += c.count > options.maxLeafSize;
                if (uint64_t(c.reference) + c.count > count) FAIL("leaf past the primitive array");
                Aabb tight;
                for (uint32_t s = c.reference; s < c.reference + c.count; ++s) {
                    ++slotCovered[s];
                    tight.extend(prims[bvh.primOrder[s]]);
                }
                looseBoxes += !contains(c.box, tight) || !sameBox(c.box, tight);
                ++stats.leafCount;
                stats.depth = std::max(stats.depth, item.depth + 1);
            } else {
                if (c.reference == 0 || c.reference >= bvh.nodes.size()) FAIL("bad node reference " << c.reference);
                ++references[c.reference];
                const gpu::BvhNode& inner = bvh.nodes[c.reference];
                Aabb tight = child(inner, 0).box;
                tight.extend(child(inner, 1).box);
                looseBoxes += !contains(c.box, tight) || !sameBox(c.box, tight);
                if (references[c.reference] > 1) FAIL("node " << c.reference << " referenced twice");  // or a cycle
                stack.push_back({c.reference, item.depth + 1});
            }
        }
    }
    stats.sahCost += 1.0;  // the root node itself
    CHECK(oversizedLeaves == 0);
    CHECK(looseBoxes == 0);  // every stored box must hold its contents, and the builder makes them tight
    CHECK(sameBox(rootBox, all));
    CHECK(std::all_of(references.begin() + 1, references.end(), [](uint32_t r) { return r == 1; }));
    CHECK(std::all_of(slotCovered.begin(), slotCovered.end(), [](uint32_t s) { return s == 1; }));
    CHECK(stats.depth == bvh.depth);
    CHECK(stats.depth <= gpu::BVH_MAX_DEPTH);
    CHECK(stats.leafCount == bvh.leafCount);
    return stats;
}

std::vector<Aabb> randomBoxes(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> position(-100.0f, 100.0f);
    std::uniform_real_distribution<float> size(0.0f, 1.0f);
    std::vector<Aabb> boxes(count);
    for (Aabb& b : boxes) {
        const glm::vec3 c(position(rng), position(rng), position(rng));
        // Mostly small boxes with a few large ones, as in real meshes.
        const float s = 0.01f + 20.0f * std::pow(size(rng), 8.0f);
        const glm::vec3 h(s * size(rng), s * size(rng), s * size(rng));
        b = {c - h, c + h};
    }
    return boxes;
}

bool identical(const Bvh& a, const Bvh& b) {
    return a.nodes.size() == b.nodes.size() && a.primOrder == b.primOrder && a.depth == b.depth &&
           a.leafCount == b.leafCount &&
           std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(gpu::BvhNode)) == 0;
}

// Reference cost: object-median splits on the widest centroid axis down to maxLeafSize.
double medianTreeCost(std::vector<Aabb> boxes, uint32_t maxLeafSize) {
    Aabb all;
    for (const Aabb& b : boxes) all.extend(b);
    const double rootArea = all.halfArea();
    double cost = 1.0;
    struct Span {
        size_t begin, end;
    };
    std::vector<Span> stack{{0, boxes.size()}};
    while (!stack.empty()) {
        const Span s = stack.back();
        stack.pop_back();
        Aabb centroids;
        for (size_t i = s.begin; i < s.end; ++i) centroids.extend(boxes[i].center());
        const glm::vec3 e = centroids.hi - centroids.lo;
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        const size_t mid = (s.begin + s.end) / 2;
        std::nth_element(boxes.begin() + s.begin, boxes.begin() + mid, boxes.begin() + s.end,
                         [axis](const Aabb& a, const Aabb& b) { return a.center()[axis] < b.center()[axis]; });
        for (const Span half : {Span{s.begin, mid}, Span{mid, s.end}}) {
            Aabb box;
            for (size_t i = half.begin; i < half.end; ++i) box.extend(boxes[i]);
            const size_t n = half.end - half.begin;
            const bool leaf = n <= maxLeafSize;
            cost += box.halfArea() / rootArea * (leaf ? double(n) : 1.0);
            if (!leaf) stack.push_back(half);
        }
    }
    return cost;
}

}  // namespace

TEST_CASE("bvh: random boxes of many sizes satisfy the node contract") {
    for (uint32_t count : {0u, 1u, 2u, 7u, 8u, 9u, 1000u, 100000u}) {
        CAPTURE(count);
        const std::vector<Aabb> boxes = randomBoxes(count, 17 + count);
        const Bvh bvh = buildBinnedSah(boxes);
        const TreeStats stats = checkBvh(bvh, boxes);
        if (count == 1) {
            CHECK(bvh.nodes.size() == 1);
            CHECK(bvh.depth == 2);
        }
        if (count >= 1000) CHECK(stats.depth >= 10);  // a real tree, not one long leaf list
    }
}

TEST_CASE("bvh: leaf size and bin count options are honoured") {
    const std::vector<Aabb> boxes = randomBoxes(5000, 3);
    for (uint32_t leaf : {1u, 2u, 4u, 8u})
        for (uint32_t bins : {2u, 8u, 16u, 32u}) {
            CAPTURE(leaf);
            CAPTURE(bins);
            BuildOptions options;
            options.maxLeafSize = leaf;
            options.binCount = bins;
            options.traversalCost = 4.0f;  // favours big leaves, so maxLeafSize is what stops them
            options.parallelThreshold = 256;
            checkBvh(buildBinnedSah(boxes, options), boxes, options);
        }
    BuildOptions bad;
    bad.binCount = 1;
    CHECK_THROWS_AS(buildBinnedSah(boxes, bad), std::invalid_argument);
    bad = {};
    bad.maxLeafSize = gpu::BVH_MAX_LEAF_SIZE + 1;
    CHECK_THROWS_AS(buildBinnedSah(boxes, bad), std::invalid_argument);
}

TEST_CASE("bvh: degenerate inputs") {
    SUBCASE("identical boxes") {
        const std::vector<Aabb> boxes(100000, Aabb{glm::vec3(1, 2, 3), glm::vec3(4, 5, 6)});
        const Bvh bvh = buildBinnedSah(boxes);
        checkBvh(bvh, boxes);
        // No plane separates equal centroids, so the range is halved: 14 times takes 100000 below 8.
        CHECK(bvh.leafCount == 1u << 14);
        CHECK(bvh.depth == 15);
    }
    SUBCASE("points at one location") {
        for (uint32_t count : {2u, 9u, 5000u}) {
            const std::vector<Aabb> boxes(count, Aabb{glm::vec3(-7.0f), glm::vec3(-7.0f)});
            checkBvh(buildBinnedSah(boxes), boxes);
        }
    }
    SUBCASE("points along a line") {
        std::vector<Aabb> boxes(100000);
        for (uint32_t i = 0; i < boxes.size(); ++i) boxes[i] = {glm::vec3(float(i), 0, 0), glm::vec3(float(i), 0, 0)};
        std::shuffle(boxes.begin(), boxes.end(), std::mt19937(5));
        const TreeStats stats = checkBvh(buildBinnedSah(boxes), boxes);
        CHECK(stats.depth <= 24);  // zero-area ranges still split evenly
    }
    SUBCASE("boxes along a diagonal") {
        std::vector<Aabb> boxes(100000);
        for (uint32_t i = 0; i < boxes.size(); ++i) boxes[i] = {glm::vec3(float(i)), glm::vec3(float(i) + 0.5f)};
        checkBvh(buildBinnedSah(boxes), boxes);
    }
    SUBCASE("boxes at extreme coordinates") {
        std::vector<Aabb> boxes = randomBoxes(1000, 9);
        for (Aabb& b : boxes) b = {b.lo * 1e36f, b.hi * 1e36f};
        boxes.push_back({glm::vec3(-FLT_MAX), glm::vec3(FLT_MAX)});
        checkBvh(buildBinnedSah(boxes), boxes);
    }
}

TEST_CASE("bvh: geometric sequences hit the depth limit and stop there") {
    // Each box is 1.5x further out than the last, so SAH keeps peeling off the outermost one or two:
    // without the limit the tree would be about 100 levels deep. Two bins are needed for that: with
    // 16, each level peels off log_1.5(16) ~ 7 boxes and float range ends before depth 48 is reached.
    for (uint32_t leaf : {1u, 8u}) {
        CAPTURE(leaf);
        std::vector<Aabb> boxes;
        for (int i = 0; i < 200; ++i) {
            const float x = std::pow(1.5f, float(i));
            boxes.push_back({glm::vec3(x), glm::vec3(x * 1.1f)});
        }
        BuildOptions options;
        options.maxLeafSize = leaf;
        options.binCount = 2;
        const TreeStats stats = checkBvh(buildBinnedSah(boxes, options), boxes, options);
        CHECK(stats.depth == gpu::BVH_MAX_DEPTH);
    }
}

TEST_CASE("bvh: the build is deterministic across thread counts and task splits") {
    const std::vector<Aabb> boxes = randomBoxes(100000, 11);
    BuildOptions fine;
    fine.parallelThreshold = 64;  // many small tasks, so scheduling order varies a lot
    BuildOptions serial;
    serial.parallelThreshold = UINT32_MAX;
    const Bvh reference = buildBinnedSah(boxes);
    CHECK(identical(reference, buildBinnedSah(boxes)));
    CHECK(identical(reference, buildBinnedSah(boxes, fine)));
    CHECK(identical(reference, buildBinnedSah(boxes, serial)));
    {
        tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
        CHECK(identical(reference, buildBinnedSah(boxes)));
        CHECK(identical(reference, buildBinnedSah(boxes, fine)));
    }
}

TEST_CASE("bvh: two separated clusters split at the root") {
    std::vector<Aabb> boxes = randomBoxes(1000, 21);
    for (uint32_t i = 0; i < boxes.size(); ++i) {
        const glm::vec3 shift(i % 2 ? 1000.0f : -1000.0f, 0, 0);  // interleaved in the input order
        boxes[i] = {boxes[i].lo + shift, boxes[i].hi + shift};
    }
    const Bvh bvh = buildBinnedSah(boxes);
    checkBvh(bvh, boxes);
    // Both root children are inner nodes; the primitives under each are one cluster.
    const Child left = child(bvh.nodes[0], 0), right = child(bvh.nodes[0], 1);
    REQUIRE(!left.leaf());
    REQUIRE(!right.leaf());
    CHECK(left.box.hi.x < 0.0f);
    CHECK(right.box.lo.x > 0.0f);
    // Preorder layout: the left subtree's leaves hold the first half of primOrder.
    uint32_t misplaced = 0;
    for (uint32_t s = 0; s < boxes.size(); ++s) misplaced += bvh.primOrder[s] % 2 != (s < 500 ? 0u : 1u);
    CHECK(misplaced == 0);
}

TEST_CASE("bvh: SAH cost is no worse than object-median splits") {
    // A jittered grid, where median splits are already good, and clustered boxes, where SAH should win
    // clearly. Both trees are costed the same way: traversal 1 per inner node, 1 per primitive test.
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
    std::vector<Aabb> grid;
    for (int x = 0; x < 32; ++x)
        for (int y = 0; y < 32; ++y)
            for (int z = 0; z < 32; ++z) {
                const glm::vec3 c = glm::vec3(x, y, z) * 2.0f + glm::vec3(jitter(rng), jitter(rng), jitter(rng));
                grid.push_back({c - 0.5f, c + 0.5f});
            }
    std::vector<Aabb> clusters = randomBoxes(30000, 8);
    for (uint32_t i = 0; i < clusters.size(); ++i) {
        const float scale = i % 10 == 0 ? 1.0f : 0.02f;  // 90% packed into a small region
        clusters[i] = {clusters[i].lo * scale, clusters[i].hi * scale};
    }
    const double gridSah = checkBvh(buildBinnedSah(grid), grid).sahCost;
    const double gridMedian = medianTreeCost(grid, gpu::BVH_MAX_LEAF_SIZE);
    const double clusterSah = checkBvh(buildBinnedSah(clusters), clusters).sahCost;
    const double clusterMedian = medianTreeCost(clusters, gpu::BVH_MAX_LEAF_SIZE);
    MESSAGE("grid SAH " << gridSah << " vs median " << gridMedian << "; clusters " << clusterSah << " vs " << clusterMedian);
    CHECK(gridSah <= gridMedian);              // measured 93 vs 138
    CHECK(clusterSah <= 0.6 * clusterMedian);  // measured 37 vs 88
}

}  // namespace ripple::bvh

#include "core/bvh/BoxClusters.h"

namespace ripple::bvh {

TEST_CASE("box clusters cover every box with at most the asked number, tightly, dropping empty ones") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> position(-100.0f, 100.0f), size(0.0f, 3.0f);
    std::vector<Aabb> boxes(1000);
    for (Aabb& b : boxes) {
        b.lo = {position(random), position(random), position(random)};
        b.hi = b.lo + glm::vec3(size(random), size(random), size(random));
    }
    boxes.push_back(Aabb{});  // empty: dropped
    for (const size_t most : {size_t(1), size_t(7), size_t(64), size_t(5000)}) {
        const std::vector<Aabb> clusters = clusterBoxes(boxes, most);
        CHECK(clusters.size() == std::min(most, boxes.size() - 1));
        size_t covered = 0;
        for (size_t i = 0; i + 1 < boxes.size(); ++i)
            covered += std::any_of(clusters.begin(), clusters.end(), [&](const Aabb& c) {
                return glm::all(glm::lessThanEqual(c.lo, boxes[i].lo)) && glm::all(glm::greaterThanEqual(c.hi, boxes[i].hi));
            });
        CHECK(covered == boxes.size() - 1);
        for (const Aabb& c : clusters) CHECK_FALSE(c.empty());
    }
    // Boxes in 8 small blobs at the corners of a 200-unit cube: 64 clusters follow the blobs, so together
    // they cover under 1% of the union's volume.
    std::vector<Aabb> blobs;
    std::uniform_real_distribution<float> offset(-5.0f, 5.0f);
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 corner(i & 1 ? 100.0f : -100.0f, i & 2 ? 100.0f : -100.0f, i & 4 ? 100.0f : -100.0f);
        const glm::vec3 lo = corner + glm::vec3(offset(random), offset(random), offset(random));
        blobs.push_back({lo, lo + glm::vec3(size(random), size(random), size(random))});
    }
    Aabb all;
    for (const Aabb& b : blobs) all.extend(b);
    const auto volumeOf = [](const Aabb& c) { return double(c.hi.x - c.lo.x) * (c.hi.y - c.lo.y) * (c.hi.z - c.lo.z); };
    double volume = 0.0;
    for (const Aabb& c : clusterBoxes(blobs, 64)) volume += volumeOf(c);
    CHECK(volume < 0.01 * volumeOf(all));
    CHECK(clusterBoxes(boxes, 0).empty());
    CHECK(clusterBoxes(std::vector<Aabb>{}, 8).empty());
}

}  // namespace ripple::bvh
