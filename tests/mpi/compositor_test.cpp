// mpi/Compositor against a direct reference: every rank's RGBA-z image gathered on rank 0 and blended pixel
// by pixel (fragments in rank order, stably sorted by depth, front to back). Every method valid for the
// rank count must give that image bit for bit, on a size that is not a multiple of the 64-pixel words,
// with transparency, equal depths on several ranks and rank 0's visible background. Run under mpirun with
// 1-4 ranks.
#include "mpi/Communicator.h"
#include "mpi/Compositor.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

using namespace ripple;

namespace {

struct Size {
    uint32_t width, height;
};

struct Image {
    std::vector<float> rgba, depth;
};

// Rank r covers a pixel where a hash says so; a third of the covered pixels are half transparent; depths
// come from 4 levels, so ranks often tie. Rank 0's background is a visible grey.
Image makeImage(Size size, uint32_t rank, bool empty) {
    const size_t pixels = size_t(size.width) * size.height;
    Image image{std::vector<float>(pixels * 4, 0.0f), std::vector<float>(pixels, INFINITY)};
    for (size_t p = 0; p < pixels; ++p) {
        uint32_t h = uint32_t(p) * 2654435761u ^ (rank + 1) * 2246822519u;
        h ^= h >> 15;
        h *= 2246822519u;
        h ^= h >> 13;
        float* c = &image.rgba[p * 4];
        if (!empty && (h & 3u) != 0) {
            const float alpha = h % 3 == 0 ? 0.5f : 1.0f;
            c[0] = alpha * float((h >> 8) & 0xFF) / 255.0f;
            c[1] = alpha * float(rank + 1) / 8.0f;
            c[2] = alpha * 0.25f;
            c[3] = alpha;
            image.depth[p] = 1.0f + float((h >> 20) & 3u);
        } else if (rank == 0) {
            c[0] = c[1] = c[2] = 0.1f;
            c[3] = 1.0f;
        }
    }
    return image;
}

std::vector<float> toFloats(const std::vector<uint8_t>& bytes, size_t from, size_t count) {
    std::vector<float> values(count);
    std::memcpy(values.data(), bytes.data() + from, count * sizeof(float));
    return values;
}

// The reference on rank 0 (empty elsewhere): rgba then depth per pixel.
struct Composite {
    std::vector<float> rgba, depth;
};

Composite reference(const mpi::Communicator& world, const Image& mine) {
    const size_t pixels = mine.depth.size();
    std::vector<uint8_t> bytes(pixels * 5 * sizeof(float));
    std::memcpy(bytes.data(), mine.rgba.data(), pixels * 16);
    std::memcpy(bytes.data() + pixels * 16, mine.depth.data(), pixels * 4);
    const std::vector<std::vector<uint8_t>> all = world.gatherToRoot(bytes);
    Composite out;
    if (world.rank() != 0) return out;
    out.rgba.assign(pixels * 4, 0.0f);
    out.depth.assign(pixels, INFINITY);
    struct Fragment {
        float rgba[4];
        float depth;
    };
    for (size_t p = 0; p < pixels; ++p) {
        std::vector<Fragment> fragments;
        for (size_t r = 0; r < all.size(); ++r) {
            const std::vector<float> c = toFloats(all[r], p * 16, 4);
            const float d = toFloats(all[r], pixels * 16 + p * 4, 1)[0];
            if (std::isinf(d) && !(r == 0 && c[3] != 0.0f)) continue;
            fragments.push_back({{c[0], c[1], c[2], c[3]}, d});
        }
        std::stable_sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.depth < b.depth; });
        float* color = &out.rgba[p * 4];
        for (const Fragment& f : fragments) {
            const float transmitted = 1.0f - color[3];
            for (int c = 0; c < 4; ++c) color[c] += transmitted * f.rgba[c];
            out.depth[p] = std::min(out.depth[p], f.depth);
        }
    }
    return out;
}

}  // namespace

// Sizes: not a multiple of the 64-pixel words; tiny (parts of no pixel at 3-4 ranks); and back, resizing
// the same compositor between composites.
TEST_CASE("compositing: every method gives the reference image bit for bit; an empty rank sends no fragment") {
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), n = uint32_t(world.size());
    std::vector<mpi::CompositeMethod> methods = {mpi::CompositeMethod::Auto, mpi::CompositeMethod::DirectSend,
                                                 mpi::CompositeMethod::RadixK};
    if (std::has_single_bit(n)) methods.push_back(mpi::CompositeMethod::BinarySwap);
    for (const bool lastEmpty : {false, true}) {
        for (const mpi::CompositeMethod method : methods) {
            mpi::Compositor compositor(world, method);
            for (const Size size : {Size{131, 67}, Size{5, 3}, Size{131, 67}}) {
                CAPTURE(mpi::compositeMethodName(method));
                CAPTURE(lastEmpty);
                CAPTURE(size.width);
                const size_t pixels = size_t(size.width) * size.height;
                const Image mine = makeImage(size, rank, lastEmpty && n > 1 && rank == n - 1);
                const Composite expected = reference(world, mine);
                compositor.resize(size.width, size.height);
                compositor.composite(mine.rgba, mine.depth);
                compositor.composite(mine.rgba, mine.depth);  // again, with the buffers of the first
                // Only pixels with fragments travel: in one round, a rank with nothing sends no fragment
                // (in later rounds it forwards those it was sent).
                if (lastEmpty && n > 1 && rank == n - 1 && compositor.rounds().size() == 1)
                    CHECK(compositor.fragmentsSent() == 0);
                if (!lastEmpty && n > 1 && pixels > 64 * n) CHECK(compositor.fragmentsSent() > 0);
                if (rank != 0) continue;
                REQUIRE(compositor.rgba().size() == pixels * 4);
                CHECK(std::memcmp(compositor.rgba().data(), expected.rgba.data(), pixels * 16) == 0);
                CHECK(std::memcmp(compositor.depth().data(), expected.depth.data(), pixels * 4) == 0);
            }
        }
    }
}

TEST_CASE("compositing: rounds for each method and rank count") {
    using M = mpi::CompositeMethod;
    CHECK(mpi::compositeRounds(1, M::Auto).empty());
    CHECK(mpi::compositeRounds(4, M::DirectSend) == std::vector<uint32_t>{4});
    CHECK(mpi::compositeRounds(8, M::BinarySwap) == std::vector<uint32_t>{2, 2, 2});
    CHECK_THROWS_AS(mpi::compositeRounds(6, M::BinarySwap), std::invalid_argument);
    CHECK(mpi::compositeRounds(6, M::Auto) == std::vector<uint32_t>{6});  // up to 8: direct send
    CHECK(mpi::compositeRounds(12, M::RadixK) == std::vector<uint32_t>{6, 2});
    CHECK(mpi::compositeRounds(64, M::RadixK) == std::vector<uint32_t>{8, 8});
    CHECK(mpi::compositeRounds(1000, M::RadixK) == std::vector<uint32_t>{8, 5, 5, 5});
    CHECK(mpi::compositeRounds(13, M::RadixK) == std::vector<uint32_t>{13});
}
