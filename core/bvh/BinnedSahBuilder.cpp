// Binned SAH BVH builder (Wald 2007): sibling subtrees are oneTBB tasks, large ranges are binned in
// parallel, and the result is written in the two-child node layout of shaders/shared/bvh.h.
#include "core/bvh/BinnedSahBuilder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cfloat>
#include <memory>
#include <stdexcept>
#include <string>

namespace ripple::bvh {
namespace {

constexpr uint32_t kMaxBins = 32;  // bins live on the stack of each binning task
constexpr uint32_t kNoParent = ~0u;

// The build partitions these records rather than indices into the input, so every level streams
// through contiguous memory instead of gathering boxes at random. 32 bytes each: the centroid is
// recomputed on the fly because two multiply-adds cost less than 50% more memory traffic per level.
struct alignas(16) Record {
    glm::vec3 lo;
    uint32_t index;
    glm::vec3 hi;
    float pad;
};

// Half-sum form so boxes near FLT_MAX cannot overflow to infinity.
inline glm::vec3 centroid(const Record& r) { return r.lo * 0.5f + r.hi * 0.5f; }

struct Range {
    uint32_t begin = 0, end = 0;
    Aabb bounds;     // of the primitive boxes
    Aabb centroids;  // of the primitive centroids; binning spans this
    uint32_t count() const { return end - begin; }
};

// Maps a centroid coordinate to its bin. Binning and partitioning both call this, so a primitive can
// never land on different sides of the plane in the two passes.
struct BinMap {
    glm::vec3 origin{0.0f};
    glm::vec3 scale{0.0f};  // 0 on axes where all centroids coincide
    float lastBin = 0.0f;

    BinMap() = default;
    BinMap(const Aabb& centroids, uint32_t binCount) : origin(centroids.lo), lastBin(float(binCount - 1)) {
        const glm::vec3 extent = centroids.hi - centroids.lo;
        // Slightly under binCount so the largest centroid maps to the last bin, not one past it.
        const float span = float(binCount) * (1.0f - 1e-5f);
        for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? span / extent[a] : 0.0f;
    }
    bool splittable() const { return scale.x > 0.0f || scale.y > 0.0f || scale.z > 0.0f; }
    uint32_t operator()(float c, int axis) const {
        float t = (c - origin[axis]) * scale[axis];
        t = t < lastBin ? t : lastBin;  // also sends NaN (inf * 0 on absurd extents) to a valid bin
        return t > 0.0f ? uint32_t(t) : 0u;
    }
};

struct Bin {
    glm::vec3 lo, hi;
    uint32_t count;
};

// Bins of all three axes; only the first binCount of each axis are initialised and used.
struct Bins {
    std::array<std::array<Bin, kMaxBins>, 3> axis;
    uint32_t binCount = 0;

    explicit Bins(uint32_t bins) : binCount(bins) {
        for (auto& bins3 : axis)
            for (uint32_t b = 0; b < binCount; ++b) bins3[b] = {glm::vec3(FLT_MAX), glm::vec3(-FLT_MAX), 0};
    }
    void add(const BinMap& map, const Record* first, const Record* last) {
        for (const Record* r = first; r != last; ++r) {
            const glm::vec3 c = centroid(*r);
            for (int a = 0; a < 3; ++a) {
                Bin& bin = axis[a][map(c[a], a)];
                bin.lo = glm::min(bin.lo, r->lo);
                bin.hi = glm::max(bin.hi, r->hi);
                ++bin.count;
            }
        }
    }
    // Min/max and integer sums: the merge order, hence the thread count, cannot change the result.
    void merge(const Bins& other) {
        for (int a = 0; a < 3; ++a)
            for (uint32_t b = 0; b < binCount; ++b) {
                axis[a][b].lo = glm::min(axis[a][b].lo, other.axis[a][b].lo);
                axis[a][b].hi = glm::max(axis[a][b].hi, other.axis[a][b].hi);
                axis[a][b].count += other.axis[a][b].count;
            }
    }
};

struct Split {
    int axis = -1;      // -1: no plane separates the centroids
    uint32_t bin = 0;   // bins [0, bin] go left
    float cost = 0.0f;  // SAH cost relative to one primitive test
    Aabb left, right;   // exact boxes of the two sides, from the bins
    BinMap map;
};

void setChild(gpu::BvhNode& node, int side, const Aabb& box, uint32_t reference, uint32_t count) {
    const glm::vec4 lo(box.lo, std::bit_cast<float>(reference));
    const glm::vec4 hi(box.hi, std::bit_cast<float>(count));
    if (side == 0) { node.leftMin = lo; node.leftMax = hi; }
    else { node.rightMin = lo; node.rightMax = hi; }
}

class Builder {
public:
    Builder(Record* records, gpu::BvhNode* nodes, const BuildOptions& options)
        : records_(records), nodes_(nodes), options_(options) {}

    // Smallest k with maxLeafSize * 2^k >= count: the levels a median-split subtree needs below its top.
    uint32_t levelsBelow(uint32_t count) const {
        uint32_t k = 0;
        for (uint64_t capacity = options_.maxLeafSize; capacity < count; capacity *= 2) ++k;
        return k;
    }

    // Builds the range as the `side` child of `parent`, itself `depth` levels deep. If it becomes an
    // inner node it takes `slot`; its subtree owns slots [slot, slot + count - 1), since a subtree of n
    // primitives has at most n - 1 inner nodes. That reservation makes the layout independent of
    // which task finishes first; unused slots are squeezed out when the tree is flattened.
    void buildChild(const Range& range, uint32_t depth, uint32_t slot, gpu::BvhNode& parent, int side) {
        const uint32_t count = range.count();
        const Split split = findSplit(range);
        const bool leafAllowed = count <= options_.maxLeafSize;
        const bool leafPreferred = split.axis < 0 || float(count) <= split.cost || depth + 1 > gpu::BVH_MAX_DEPTH;
        if (leafAllowed && leafPreferred) {
            setChild(parent, side, range.bounds, range.begin, count);
            return;
        }
        setChild(parent, side, range.bounds, slot, 0);
        innerCount.fetch_add(1, std::memory_order_relaxed);
        buildInner(range, split, depth, slot);
    }

    std::atomic<uint32_t> innerCount{0};

private:
    void buildInner(const Range& range, const Split& split, uint32_t depth, uint32_t slot) {
        if (depth + std::max(levelsBelow(range.count()), 1u) > gpu::BVH_MAX_DEPTH)
            throw std::runtime_error("BVH build: " + std::to_string(range.count()) +
                                     " primitives cannot fit below depth " + std::to_string(depth) +
                                     " within BVH_MAX_DEPTH = " + std::to_string(gpu::BVH_MAX_DEPTH));
        Range left, right;
        bool fits = false;
        if (split.axis >= 0) {
            partition(range, split, left, right);
            // An SAH split can be lopsided; near the depth limit only splits that leave room for a
            // balanced subtree on both sides are taken, so the limit is never exceeded.
            const uint32_t childDepth = depth + 1;
            fits = childDepth + levelsBelow(left.count()) <= gpu::BVH_MAX_DEPTH &&
                   childDepth + levelsBelow(right.count()) <= gpu::BVH_MAX_DEPTH;
        }
        if (!fits) medianSplit(range, left, right);

        gpu::BvhNode& node = nodes_[slot];
        const uint32_t leftSlot = slot + 1, rightSlot = slot + left.count();
        if (range.count() >= options_.parallelThreshold) {
            tbb::parallel_invoke([&] { buildChild(left, depth + 1, leftSlot, node, 0); },
                                 [&] { buildChild(right, depth + 1, rightSlot, node, 1); });
        } else {
            buildChild(left, depth + 1, leftSlot, node, 0);
            buildChild(right, depth + 1, rightSlot, node, 1);
        }
    }

    Split findSplit(const Range& range) const {
        Split best;
        const uint32_t count = range.count();
        if (count < 2) return best;
        const BinMap map(range.centroids, options_.binCount);
        if (!map.splittable()) return best;

        const Record* first = records_ + range.begin;
        Bins bins(options_.binCount);
        if (count >= options_.parallelThreshold) {
            bins = tbb::parallel_reduce(
                tbb::blocked_range<uint32_t>(0, count, 4096), Bins(options_.binCount),
                [&](const tbb::blocked_range<uint32_t>& r, Bins partial) {
                    partial.add(map, first + r.begin(), first + r.end());
                    return partial;
                },
                [](Bins a, const Bins& b) { a.merge(b); return a; });
        } else {
            bins.add(map, first, first + count);
        }

        // Ranges that are points or segments have zero area for every candidate, so SAH cannot rank
        // them; the box perimeter then keeps the splits balanced instead of taking the first plane.
        const bool flat = range.bounds.halfArea() <= 0.0f;
        const auto metric = [flat](const Aabb& b) {
            if (!flat) return b.halfArea();
            const glm::vec3 d = b.hi - b.lo;
            return d.x + d.y + d.z;
        };
        const uint32_t binCount = options_.binCount;
        float bestCost = FLT_MAX;
        for (int a = 0; a < 3; ++a) {
            if (map.scale[a] == 0.0f) continue;
            const auto& axisBins = bins.axis[a];
            std::array<float, kMaxBins> rightCost;
            Aabb box;
            uint32_t n = 0;
            float cost = 0.0f;
            // Small ranges leave most bins empty; an empty bin repeats its neighbour's candidate, and
            // skipping it keeps the choice identical (ties go to the first plane) at a fraction of the work.
            for (uint32_t b = binCount - 1; b > 0; --b) {
                if (axisBins[b].count > 0) {
                    box.extend(Aabb{axisBins[b].lo, axisBins[b].hi});
                    n += axisBins[b].count;
                    cost = metric(box) * float(n);
                }
                rightCost[b - 1] = cost;
            }
            box = Aabb{};
            n = 0;
            for (uint32_t b = 0; b + 1 < binCount; ++b) {
                if (axisBins[b].count == 0) continue;
                box.extend(Aabb{axisBins[b].lo, axisBins[b].hi});
                n += axisBins[b].count;
                if (n == count) break;
                cost = metric(box) * float(n) + rightCost[b];
                if (cost < bestCost) { bestCost = cost; best.axis = a; best.bin = b; }
            }
        }
        if (best.axis < 0) return best;

        for (uint32_t b = 0; b < binCount; ++b) {
            const Bin& bin = bins.axis[best.axis][b];
            (b <= best.bin ? best.left : best.right).extend(Aabb{bin.lo, bin.hi});
        }
        const float parentMetric = metric(range.bounds);
        best.cost = options_.traversalCost + (parentMetric > 0.0f ? bestCost / parentMetric : 0.0f);
        best.map = map;
        return best;
    }

    // Hoare partition by the split plane; it also gathers the children's centroid bounds, which the
    // bins do not give exactly, so no extra pass over the records is needed.
    void partition(const Range& range, const Split& split, Range& left, Range& right) const {
        const int axis = split.axis;
        const auto goesLeft = [&](const Record& r) {
            return split.map(r.lo[axis] * 0.5f + r.hi[axis] * 0.5f, axis) <= split.bin;
        };
        uint32_t i = range.begin, j = range.end;
        Aabb leftCentroids, rightCentroids;
        for (;;) {
            while (i < j && goesLeft(records_[i])) leftCentroids.extend(centroid(records_[i++]));
            while (i < j && !goesLeft(records_[j - 1])) rightCentroids.extend(centroid(records_[--j]));
            if (i >= j) break;
            std::swap(records_[i], records_[j - 1]);
            leftCentroids.extend(centroid(records_[i++]));
            rightCentroids.extend(centroid(records_[--j]));
        }
        left = {range.begin, i, split.left, leftCentroids};
        right = {i, range.end, split.right, rightCentroids};
    }

    // Object median on the widest centroid axis: the fallback when no plane separates the centroids,
    // and the split that keeps a subtree balanced near the depth limit.
    void medianSplit(const Range& range, Range& left, Range& right) const {
        const glm::vec3 extent = range.centroids.hi - range.centroids.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const uint32_t mid = range.begin + range.count() / 2;
        std::nth_element(records_ + range.begin, records_ + mid, records_ + range.end,
                         [axis](const Record& a, const Record& b) { return centroid(a)[axis] < centroid(b)[axis]; });
        left = {range.begin, mid, {}, {}};
        right = {mid, range.end, {}, {}};
        for (Range* side : {&left, &right})
            for (uint32_t i = side->begin; i < side->end; ++i) {
                side->bounds.extend(Aabb{records_[i].lo, records_[i].hi});
                side->centroids.extend(centroid(records_[i]));
            }
    }

    Record* records_;
    gpu::BvhNode* nodes_;
    const BuildOptions& options_;
};

struct RootBounds {
    Aabb bounds, centroids;
};

}  // namespace

Bvh buildBinnedSah(std::span<const Aabb> primBounds, const BuildOptions& options) {
    if (options.binCount < 2 || options.binCount > kMaxBins)
        throw std::invalid_argument("BVH build: binCount must be in [2, " + std::to_string(kMaxBins) + "]");
    if (options.maxLeafSize < 1 || options.maxLeafSize > gpu::BVH_MAX_LEAF_SIZE)
        throw std::invalid_argument("BVH build: maxLeafSize must be in [1, BVH_MAX_LEAF_SIZE]");
    if (primBounds.size() >= kNoParent)
        throw std::invalid_argument("BVH build: too many primitives for 32-bit references");

    Bvh bvh;
    const auto count = uint32_t(primBounds.size());
    if (count == 0) return bvh;

    auto records = std::make_unique_for_overwrite<Record[]>(count);
    const RootBounds root = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(0, count, 4096), RootBounds{},
        [&](const tbb::blocked_range<uint32_t>& r, RootBounds acc) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) {
                records[i] = {primBounds[i].lo, i, primBounds[i].hi, 0.0f};
                acc.bounds.extend(primBounds[i]);
                acc.centroids.extend(centroid(records[i]));
            }
            return acc;
        },
        [](RootBounds a, const RootBounds& b) {
            a.bounds.extend(b.bounds);
            a.centroids.extend(b.centroids);
            return a;
        });
    bvh.bounds = root.bounds;

    // Inner nodes go to reserved slots (see buildChild), then are copied out depth-first without gaps.
    // The root is built as the left child of a holder node, which becomes the output root as is when
    // the whole input fits one leaf.
    auto slots = std::make_unique_for_overwrite<gpu::BvhNode[]>(count);
    Builder builder(records.get(), slots.get(), options);
    if (1 + builder.levelsBelow(count) > gpu::BVH_MAX_DEPTH)
        throw std::runtime_error("BVH build: " + std::to_string(count) + " primitives exceed BVH_MAX_DEPTH");
    gpu::BvhNode holder;
    setChild(holder, 0, Aabb{}, 0, 0);
    setChild(holder, 1, Aabb{}, 0, 0);
    builder.buildChild(Range{0, count, root.bounds, root.centroids}, 1, 0, holder, 0);

    bvh.primOrder.resize(count);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, 16384), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i < r.end(); ++i) bvh.primOrder[i] = records[i].index;
    });

    if (std::bit_cast<uint32_t>(holder.leftMax.w) > 0) {
        bvh.nodes.push_back(holder);
        bvh.depth = 2;
        bvh.leafCount = 1;
        return bvh;
    }

    // Preorder walk: pushing the right child first emits every left subtree before its sibling.
    struct Item {
        uint32_t slot, depth, parent;
        int side;
    };
    std::vector<Item> stack{{0, 1, kNoParent, 0}};
    bvh.nodes.reserve(builder.innerCount.load());
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const auto index = uint32_t(bvh.nodes.size());
        bvh.nodes.push_back(slots[item.slot]);
        if (item.parent != kNoParent) {
            gpu::BvhNode& parent = bvh.nodes[item.parent];
            (item.side == 0 ? parent.leftMin : parent.rightMin).w = std::bit_cast<float>(index);
        }
        const gpu::BvhNode& node = bvh.nodes[index];
        for (int side = 1; side >= 0; --side) {
            const uint32_t reference = std::bit_cast<uint32_t>((side == 0 ? node.leftMin : node.rightMin).w);
            const uint32_t leafSize = std::bit_cast<uint32_t>((side == 0 ? node.leftMax : node.rightMax).w);
            if (leafSize > 0) {
                ++bvh.leafCount;
                bvh.depth = std::max(bvh.depth, item.depth + 1);
            } else {
                stack.push_back({reference, item.depth + 1, index, side});
            }
        }
    }
    return bvh;
}

}  // namespace ripple::bvh
