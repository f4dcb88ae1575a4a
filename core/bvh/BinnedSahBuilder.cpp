// Binned SAH BVH builder (Wald 2007): sibling subtrees are oneTBB tasks, large ranges are binned in
// parallel, and the result is written in the two-child node layout of shaders/shared/bvh.h.
#include "core/bvh/BinnedSahBuilder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <memory>
#include <stdexcept>
#include <string>

namespace ripple::bvh {
namespace {

constexpr uint32_t kMaxBins = 32;  // bins live on the stack of each binning task
constexpr uint32_t kNoParent = ~0u;

// Four float lanes for the per-primitive loops, which dominate the build time: SSE where the target has
// it, plain loops elsewhere. Lane 3 is kept at zero wherever arithmetic touches it.
#if defined(__SSE2__) || defined(_M_X64)
struct F4 {
    __m128 v;
    static F4 load(const float* p) { return {_mm_load_ps(p)}; }
    static F4 set(float x, float y, float z, float w) { return {_mm_setr_ps(x, y, z, w)}; }
    void store(float* p) const { _mm_store_ps(p, v); }
    F4 xyz() const { return {_mm_and_ps(v, _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)))}; }
    friend F4 operator+(F4 a, F4 b) { return {_mm_add_ps(a.v, b.v)}; }
    friend F4 operator-(F4 a, F4 b) { return {_mm_sub_ps(a.v, b.v)}; }
    friend F4 operator*(F4 a, F4 b) { return {_mm_mul_ps(a.v, b.v)}; }
    friend F4 min(F4 a, F4 b) { return {_mm_min_ps(a.v, b.v)}; }  // a < b ? a : b, per lane
    friend F4 max(F4 a, F4 b) { return {_mm_max_ps(a.v, b.v)}; }  // a > b ? a : b, per lane
    void truncate(int32_t* out) const { _mm_store_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(v)); }
    F4 yzx() const { return {_mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 0, 2, 1))}; }
    float sum3() const {
        return (_mm_cvtss_f32(v) + _mm_cvtss_f32(_mm_shuffle_ps(v, v, 1))) + _mm_cvtss_f32(_mm_shuffle_ps(v, v, 2));
    }
};
#else
struct F4 {
    float v[4];
    static F4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
    static F4 set(float x, float y, float z, float w) { return {{x, y, z, w}}; }
    void store(float* p) const { std::copy(v, v + 4, p); }
    F4 xyz() const { return {{v[0], v[1], v[2], 0.0f}}; }
    template <typename Op> static F4 map(F4 a, F4 b, Op op) {
        return {{op(a.v[0], b.v[0]), op(a.v[1], b.v[1]), op(a.v[2], b.v[2]), op(a.v[3], b.v[3])}};
    }
    friend F4 operator+(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x + y; }); }
    friend F4 operator-(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x - y; }); }
    friend F4 operator*(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x * y; }); }
    friend F4 min(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x < y ? x : y; }); }
    friend F4 max(F4 a, F4 b) { return map(a, b, [](float x, float y) { return x > y ? x : y; }); }
    void truncate(int32_t* out) const { for (int i = 0; i < 4; ++i) out[i] = int32_t(v[i]); }
    F4 yzx() const { return {{v[1], v[2], v[0], v[3]}}; }
    float sum3() const { return (v[0] + v[1]) + v[2]; }
};
#endif

F4 toF4(const glm::vec3& p) { return F4::set(p.x, p.y, p.z, 0.0f); }
glm::vec3 toVec3(F4 a) {
    alignas(16) float f[4];
    a.store(f);
    return {f[0], f[1], f[2]};
}
// What min and max grow from; functions rather than globals, so they fold into immediate constants.
F4 emptyLo() { return toF4(glm::vec3(FLT_MAX)); }
F4 emptyHi() { return toF4(glm::vec3(-FLT_MAX)); }

// The build partitions these records rather than indices into the input, so every level streams
// through contiguous memory instead of gathering boxes at random. The centroid is recomputed where
// needed: one add costs less than 50% more memory traffic per level.
struct alignas(16) Record {
    float lo[4];  // lo[3] holds the input index as bits; xyz() masks it off before any arithmetic
    float hi[4];  // hi[3] is 0
    uint32_t index() const { return std::bit_cast<uint32_t>(lo[3]); }
    F4 lower() const { return F4::load(lo).xyz(); }
    F4 upper() const { return F4::load(hi); }
    // Twice the centroid: only ever compared with itself, and a lone add leaves the compiler no
    // multiply-add to fuse, so every call site computes bit-identical values.
    F4 centroid() const { return lower() + upper(); }
    float centroid(int axis) const { return lo[axis] + hi[axis]; }
};

struct Range {
    Record* data = nullptr;  // the buffer holding this range: partitions alternate between two
    uint32_t begin = 0, end = 0;
    Aabb bounds;     // of the primitive boxes
    Aabb centroids;  // of the primitive centroids; binning spans this
    uint32_t count() const { return end - begin; }
};

// Maps centroids to bins. Binning and partitioning both call this, so a primitive can never land on
// different sides of the plane in the two passes.
struct BinMap {
    F4 origin{}, scale{};  // scale is 0 on axes where all centroids coincide
    F4 lastBin{};

    BinMap() = default;
    BinMap(const Aabb& centroids, uint32_t binCount) {
        const glm::vec3 extent = centroids.hi - centroids.lo;
        // Slightly under binCount so the largest centroid maps to the last bin, not one past it.
        const float span = float(binCount) * (1.0f - 1e-5f);
        glm::vec3 s;
        for (int a = 0; a < 3; ++a) s[a] = extent[a] > 0.0f ? span / extent[a] : 0.0f;
        origin = toF4(centroids.lo);
        scale = toF4(s);
        lastBin = toF4(glm::vec3(float(binCount - 1)));
    }
    // The clamp to the last bin comes first so that NaN (inf * 0 on absurd extents) lands there too.
    void operator()(F4 centroid, int32_t* bins) const {
        max(min((centroid - origin) * scale, lastBin), F4{}).truncate(bins);
    }
};

struct alignas(16) Bin {
    float lo[4], hi[4];
};

// Bins of all three axes; only the first binCount of each axis are initialised and used.
struct Bins {
    std::array<std::array<Bin, kMaxBins>, 3> box;
    std::array<std::array<uint32_t, kMaxBins>, 3> count;
    uint32_t binCount = 0;

    explicit Bins(uint32_t bins) : binCount(bins) {
        for (int a = 0; a < 3; ++a)
            for (uint32_t b = 0; b < binCount; ++b) {
                emptyLo().store(box[a][b].lo);
                emptyHi().store(box[a][b].hi);
                count[a][b] = 0;
            }
    }
    void grow(int a, uint32_t b, F4 lo, F4 hi) {
        min(F4::load(box[a][b].lo), lo).store(box[a][b].lo);
        max(F4::load(box[a][b].hi), hi).store(box[a][b].hi);
    }
    void add(const BinMap& map, const Record* first, const Record* last) {
        alignas(16) int32_t bin[4];
        for (const Record* r = first; r != last; ++r) {
            const F4 lo = r->lower(), hi = r->upper();
            map(lo + hi, bin);
            for (int a = 0; a < 3; ++a) {
                grow(a, uint32_t(bin[a]), lo, hi);
                ++count[a][bin[a]];
            }
        }
    }
    // Min/max and integer sums: the merge order, hence the thread count, cannot change the result.
    void merge(const Bins& other) {
        for (int a = 0; a < 3; ++a)
            for (uint32_t b = 0; b < binCount; ++b) {
                grow(a, b, F4::load(other.box[a][b].lo), F4::load(other.box[a][b].hi));
                count[a][b] += other.count[a][b];
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
    Builder(Record* records, Record* scratch, gpu::BvhNode* nodes, uint32_t* primOrder, const BuildOptions& options)
        : buffers_{records, scratch}, nodes_(nodes), primOrder_(primOrder), options_(options) {}

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
            for (uint32_t i = range.begin; i < range.end; ++i) primOrder_[i] = range.data[i].index();
            return;
        }
        setChild(parent, side, range.bounds, slot, 0);
        buildInner(range, split, depth, slot);
    }

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
        // More bins than primitives only add sweep work: small ranges, the bulk of all nodes, use fewer.
        const uint32_t binCount = std::min(options_.binCount, std::max(count, 4u));
        const glm::vec3 extent = range.centroids.hi - range.centroids.lo;
        if (!(extent.x > 0.0f || extent.y > 0.0f || extent.z > 0.0f)) return best;
        const BinMap map(range.centroids, binCount);

        const Record* first = range.data + range.begin;
        Bins bins(binCount);
        if (count >= options_.parallelThreshold) {
            bins = tbb::parallel_reduce(
                tbb::blocked_range<uint32_t>(0, count, 4096), Bins(binCount),
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
        // Empty boxes measure 0 through the clamp, without a branch.
        const bool flat = range.bounds.halfArea() <= 0.0f;
        const auto metric = [flat](F4 lo, F4 hi) {
            const F4 d = max(hi - lo, F4{});
            return flat ? d.sum3() : (d * d.yzx()).sum3();
        };
        float bestCost = FLT_MAX;
        for (int a = 0; a < 3; ++a) {
            if (!(extent[a] > 0.0f)) continue;
            const auto& box = bins.box[a];
            std::array<float, kMaxBins> rightCost;
            F4 lo = emptyLo(), hi = emptyHi();
            uint32_t n = 0;
            for (uint32_t b = binCount - 1; b > 0; --b) {
                lo = min(lo, F4::load(box[b].lo));
                hi = max(hi, F4::load(box[b].hi));
                n += bins.count[a][b];
                rightCost[b - 1] = metric(lo, hi) * float(n);
            }
            lo = emptyLo(), hi = emptyHi();
            n = 0;
            for (uint32_t b = 0; b + 1 < binCount; ++b) {
                lo = min(lo, F4::load(box[b].lo));
                hi = max(hi, F4::load(box[b].hi));
                n += bins.count[a][b];
                const float cost = metric(lo, hi) * float(n) + rightCost[b];
                if (cost < bestCost && n > 0 && n < count) { bestCost = cost; best.axis = a; best.bin = b; }
            }
        }
        if (best.axis < 0) return best;

        F4 lo[2] = {emptyLo(), emptyLo()}, hi[2] = {emptyHi(), emptyHi()};
        for (uint32_t b = 0; b < binCount; ++b) {
            const int side = b > best.bin;
            lo[side] = min(lo[side], F4::load(bins.box[best.axis][b].lo));
            hi[side] = max(hi[side], F4::load(bins.box[best.axis][b].hi));
        }
        best.left = {toVec3(lo[0]), toVec3(hi[0])};
        best.right = {toVec3(lo[1]), toVec3(hi[1])};
        const float parentMetric = metric(toF4(range.bounds.lo), toF4(range.bounds.hi));
        best.cost = options_.traversalCost + (parentMetric > 0.0f ? bestCost / parentMetric : 0.0f);
        best.map = map;
        return best;
    }

    // Out-of-place partition into the other buffer: left from the front, right from the back. It has no
    // data-dependent branch (a random plane side mispredicts half the time) and gathers the children's
    // centroid bounds, which the bins do not give exactly, in the same pass.
    void partition(const Range& range, const Split& split, Range& left, Range& right) const {
        const Record* src = range.data;
        Record* dst = src == buffers_[0] ? buffers_[1] : buffers_[0];
        uint32_t l = range.begin, r = range.end;
        F4 lo[2] = {emptyLo(), emptyLo()}, hi[2] = {emptyHi(), emptyHi()};
        alignas(16) int32_t bin[4];
        for (uint32_t i = range.begin; i < range.end; ++i) {
            const Record& rec = src[i];
            const F4 c = rec.centroid();
            split.map(c, bin);
            const bool goesRight = uint32_t(bin[split.axis]) > split.bin;
            // Select by mask: compilers turn the conditional form into a branch.
            const uint32_t mask = 0u - uint32_t(goesRight);
            dst[(l & ~mask) | ((r - 1) & mask)] = rec;
            l += !goesRight;
            r -= goesRight;
            lo[goesRight] = min(lo[goesRight], c);
            hi[goesRight] = max(hi[goesRight], c);
        }
        left = {dst, range.begin, l, split.left, {toVec3(lo[0]), toVec3(hi[0])}};
        right = {dst, l, range.end, split.right, {toVec3(lo[1]), toVec3(hi[1])}};
    }

    // Object median on the widest centroid axis: the fallback when no plane separates the centroids,
    // and the split that keeps a subtree balanced near the depth limit.
    void medianSplit(const Range& range, Range& left, Range& right) const {
        const glm::vec3 extent = range.centroids.hi - range.centroids.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const uint32_t mid = range.begin + range.count() / 2;
        Record* data = range.data;
        std::nth_element(data + range.begin, data + mid, data + range.end,
                         [axis](const Record& a, const Record& b) { return a.centroid(axis) < b.centroid(axis); });
        left = {data, range.begin, mid, {}, {}};
        right = {data, mid, range.end, {}, {}};
        for (Range* side : {&left, &right})
            for (uint32_t i = side->begin; i < side->end; ++i) {
                side->bounds.extend(Aabb{toVec3(data[i].lower()), toVec3(data[i].upper())});
                side->centroids.extend(toVec3(data[i].centroid()));
            }
    }

    Record* buffers_[2];
    gpu::BvhNode* nodes_;
    uint32_t* primOrder_;
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
                const Aabb& b = primBounds[i];
                records[i] = {{b.lo.x, b.lo.y, b.lo.z, std::bit_cast<float>(i)}, {b.hi.x, b.hi.y, b.hi.z, 0.0f}};
                acc.bounds.extend(b);
                acc.centroids.extend(toVec3(records[i].centroid()));
            }
            return acc;
        },
        [](RootBounds a, const RootBounds& b) {
            a.bounds.extend(b.bounds);
            a.centroids.extend(b.centroids);
            return a;
        });
    bvh.bounds = root.bounds;

    // Inner nodes go to reserved slots of bvh.nodes (see buildChild) and are then compacted in place.
    // The root is built as the left child of a holder node, which becomes the output root as is when
    // the whole input fits one leaf.
    auto scratch = std::make_unique_for_overwrite<Record[]>(count);
    bvh.nodes.resize(count - 1);
    bvh.primOrder.resize(count);
    Builder builder(records.get(), scratch.get(), bvh.nodes.data(), bvh.primOrder.data(), options);
    if (1 + builder.levelsBelow(count) > gpu::BVH_MAX_DEPTH)
        throw std::runtime_error("BVH build: " + std::to_string(count) + " primitives exceed BVH_MAX_DEPTH");
    gpu::BvhNode holder;
    setChild(holder, 0, Aabb{}, 0, 0);
    setChild(holder, 1, Aabb{}, 0, 0);
    builder.buildChild(Range{records.get(), 0, count, root.bounds, root.centroids}, 1, 0, holder, 0);

    if (std::bit_cast<uint32_t>(holder.leftMax.w) > 0) {
        bvh.nodes.assign(1, holder);
        bvh.depth = 2;
        bvh.leafCount = 1;
        return bvh;
    }

    // Preorder walk, right child pushed first so each left subtree comes out before its sibling. Slots
    // are laid out in preorder too, so a node only ever moves down onto a gap or an already moved node.
    struct Item {
        uint32_t slot, depth, parent;
        int side;
    };
    std::vector<Item> stack{{0, 1, kNoParent, 0}};
    uint32_t index = 0;
    for (; !stack.empty(); ++index) {
        const Item item = stack.back();
        stack.pop_back();
        gpu::BvhNode& node = bvh.nodes[index];
        node = bvh.nodes[item.slot];
        if (item.parent != kNoParent) {
            gpu::BvhNode& parent = bvh.nodes[item.parent];
            (item.side == 0 ? parent.leftMin : parent.rightMin).w = std::bit_cast<float>(index);
        }
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
    bvh.nodes.resize(index);
    if (bvh.nodes.capacity() > 2 * bvh.nodes.size()) bvh.nodes.shrink_to_fit();  // big leaves leave big gaps
    return bvh;
}

}  // namespace ripple::bvh
