// Deep compositing of every rank's RGBA-z image: the image each rank renders of its own share of the world
// becomes, on rank 0, the image of the whole world (no cross-rank light).
//
// Radix-k (Peterka et al. 2009): the ranks composite in rounds. In a round of group size k, the ranks form
// groups of k that hold the same pixel region; the region is cut into k parts, each member keeps one part
// and sends the other k - 1 to the members that keep them. After the last round every rank owns one region
// of the image with every rank's fragments for it, blends them and sends the result to rank 0. Direct send
// is one round with k = N; binary swap is rounds of k = 2. Only pixels that hold a fragment travel (a bit
// mask marks them), and fragments are never merged before the last round, so transparency blends in exact
// depth order whatever the rounds: every method gives the same image, bit for bit.
#pragma once

#include "mpi/Communicator.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace ripple::mpi {

enum class CompositeMethod : uint32_t {
    Auto,        // radix-k with groups of at most kMaxRadix: direct send up to kMaxRadix ranks
    DirectSend,  // one round, k = N
    BinarySwap,  // rounds of k = 2; N must be a power of two
    RadixK,      // N's prime factors combined into groups of at most kMaxRadix, largest first
};
inline constexpr uint32_t kMaxRadix = 8;
inline constexpr const char* kCompositeMethodNames = "\"auto\", \"directSend\", \"binarySwap\", \"radixK\"";
std::optional<CompositeMethod> parseCompositeMethod(std::string_view name);
const char* compositeMethodName(CompositeMethod method);

// The group size of each round for `ranks` ranks (empty for one rank). Throws std::invalid_argument for
// binary swap on a rank count that is not a power of two.
std::vector<uint32_t> compositeRounds(uint32_t ranks, CompositeMethod method);

// Alpha convention: colors are PREMULTIPLIED by alpha, and a fragment in front of another blends as
// front + (1 - front.alpha) * back; fragments at equal depth blend in rank order. A pixel with depth
// +infinity is background: only rank 0's background is kept (every rank sees the same background), and it
// sorts behind every surface. Ranks with empty worlds send only background, so they contribute nothing.
class Compositor {
public:
    // Collective: throws std::invalid_argument on every rank when the ranks' methods differ, or for binary
    // swap on a rank count that is not a power of two.
    explicit Compositor(Communicator ranks, CompositeMethod method = CompositeMethod::Auto);

    void resize(uint32_t width, uint32_t height);
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

    // Collective. rgba: width*height*4 floats (premultiplied), depth: width*height floats, rows in order.
    void composite(std::span<const float> rgba, std::span<const float> depth);

    // The whole composited image on rank 0 (empty on other ranks); depth is the nearest fragment's.
    const std::vector<float>& rgba() const { return rgba_; }
    const std::vector<float>& depth() const { return depth_; }
    // Bytes this rank sent to other ranks in the last composite (fragments, and its region to rank 0).
    uint64_t bytesSent() const { return bytesSent_; }
    // Fragments this rank sent to other ranks in the rounds of the last composite (not its blended region).
    uint64_t fragmentsSent() const { return fragmentsSent_; }
    const Communicator& ranks() const { return ranks_; }
    const std::vector<uint32_t>& rounds() const { return rounds_; }

    // A rank's pixels [first, first + count) of the image, as fragments: bit i of `words` says whether pixel
    // first + i has any; `counts` holds how many for each such pixel in order, `fragments` the fragments
    // pixel by pixel (each pixel's in rank order); the first `marked` counts and `fragmentCount` fragments
    // are used (the vectors only grow, so a steady frame allocates nothing). `first` is a multiple of 64,
    // so a part that starts at a multiple of 64 is a run of whole words.
    struct Fragment {
        float rgba[4];
        float depth;
    };
    struct DeepRegion {
        uint64_t first = 0, count = 0;
        std::vector<uint64_t> words;
        std::vector<uint16_t> counts;
        std::vector<Fragment> fragments;
        uint64_t marked = 0, fragmentCount = 0;
    };

private:
    Communicator ranks_;
    std::vector<uint32_t> rounds_;
    uint32_t width_ = 0, height_ = 0;
    std::vector<float> rgba_, depth_;
    uint64_t bytesSent_ = 0, fragmentsSent_ = 0;
    // Working buffers of composite(), kept between frames.
    DeepRegion mine_, merged_;
    std::vector<uint8_t> send_, received_;
    std::vector<uint64_t> sendCounts_, receivedOffsets_;
};

}  // namespace ripple::mpi
