// Radix-k deep compositing (see Compositor.h). Wire format of one part of a region, [first, last): a header
// of two uint64 (pixels with fragments, fragments), the part's words of the bit mask, a uint16 count per
// marked pixel (padded to 8 bytes), then the 20-byte fragments (padded to 8 bytes). Part boundaries are
// multiples of 64 pixels (bar the image's end), so a part's mask is whole words of its region's mask. The
// last message, each rank's blended region to rank 0, is the mask and one fragment per marked pixel; rank 0
// blends its own region straight into the image.
#include "mpi/Compositor.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::mpi {

namespace {

using Fragment = Compositor::Fragment;
using DeepRegion = Compositor::DeepRegion;
static_assert(sizeof(Fragment) == 20);

constexpr uint64_t kPixelsPerWord = 64;

uint64_t wordsFor(uint64_t pixels) { return (pixels + kPixelsPerWord - 1) / kPixelsPerWord; }

template <class T>
void growTo(std::vector<T>& v, uint64_t size) {
    if (v.size() < size) v.resize(size);
}
uint64_t padded8(uint64_t bytes) { return (bytes + 7) / 8 * 8; }

// Start of part j of k of [first, first + count), rounded down to a multiple of 64 pixels.
uint64_t partBegin(uint64_t first, uint64_t count, uint32_t j, uint32_t k) {
    if (j == 0) return first;
    if (j >= k) return first + count;
    return first + count * j / k / kPixelsPerWord * kPixelsPerWord;
}

struct Span {
    uint64_t first = 0, count = 0;
};

// The region rank `rank` owns after the rounds: in the round of stride s (the product of the earlier
// group sizes) and group size k, its digit (rank / s) % k picks the part it keeps.
Span finalRegion(uint32_t rank, uint64_t pixels, const std::vector<uint32_t>& rounds) {
    Span region{0, pixels};
    uint32_t stride = 1;
    for (uint32_t k : rounds) {
        const uint32_t digit = rank / stride % k;
        const uint64_t begin = partBegin(region.first, region.count, digit, k);
        region = {begin, partBegin(region.first, region.count, digit + 1, k) - begin};
        stride *= k;
    }
    return region;
}

// Bit i of the result is kept[i] (each 0 or 1): eight flags at a time, gathered by a multiplication.
uint64_t packBits(const uint8_t (&kept)[kPixelsPerWord]) {
    uint64_t mask = 0;
    for (unsigned byte = 0; byte < 8; ++byte) {
        uint64_t flags = 0;  // kept[byte * 8 + i] in byte i (one load on a little-endian machine)
        for (unsigned i = 0; i < 8; ++i) flags |= uint64_t(kept[byte * 8 + i]) << (8 * i);
        mask |= ((flags * 0x0102040810204080ull) >> 56) << (byte * 8);
    }
    return mask;
}

// `marks ? fragment : otherwise` (marks 0 or 1) by a mask: compilers turn a condition into a branch, which
// mispredicts half the time where the ranks' pixels are scattered.
const uint8_t* select(uint64_t marks, const uint8_t* fragment, const uint8_t* otherwise) {
    const auto a = reinterpret_cast<uintptr_t>(fragment), b = reinterpret_cast<uintptr_t>(otherwise);
    return reinterpret_cast<const uint8_t*>(b ^ ((a ^ b) & (0 - uintptr_t(marks))));
}

template <class T>
T load(const uint8_t* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

// Read access to the fragments of a part, whether in a DeepRegion or a received message.
struct PartView {
    const uint8_t* words = nullptr;      // uint64 each
    const uint8_t* counts = nullptr;     // uint16 each
    const uint8_t* fragments = nullptr;  // Fragment each
    uint64_t wordCount = 0, marked = 0, fragmentCount = 0;
    uint64_t word(uint64_t w) const { return load<uint64_t>(words + w * 8); }
    uint16_t count(uint64_t i) const { return load<uint16_t>(counts + i * 2); }
    Fragment fragment(uint64_t i) const { return load<Fragment>(fragments + i * sizeof(Fragment)); }
};

// Where a word of a region's mask starts in its counts and fragments: found by a scan from a cursor that
// only moves forward (parts are taken in order).
struct Cursor {
    uint64_t word = 0, marked = 0, fragments = 0;
};

void advanceTo(const DeepRegion& region, uint64_t toWord, Cursor& cursor) {
    for (; cursor.word < toWord; ++cursor.word) {
        const auto marked = uint64_t(std::popcount(region.words[cursor.word]));
        for (uint64_t i = 0; i < marked; ++i) cursor.fragments += region.counts[cursor.marked + i];
        cursor.marked += marked;
    }
}

// The words of part [begin, end) of `region`: begin is a multiple of 64 pixels from region.first.
uint64_t firstWord(const DeepRegion& region, uint64_t begin) { return (begin - region.first) / kPixelsPerWord; }
uint64_t endWord(const DeepRegion& region, uint64_t end) { return wordsFor(end - region.first); }

// Writes part [begin, end) of `region` in the wire format at `offset` of `out` (grown as needed, never
// cleared: every byte of the part is written); `at` moves to its end. Returns the bytes written.
uint64_t writePart(const DeepRegion& region, uint64_t begin, uint64_t end, Cursor& at, std::vector<uint8_t>& out,
                   uint64_t offset) {
    advanceTo(region, firstWord(region, begin), at);
    const Cursor start = at;
    advanceTo(region, endWord(region, end), at);
    const uint64_t words = at.word - start.word, marked = at.marked - start.marked;
    const uint64_t fragments = at.fragments - start.fragments;
    const uint64_t bytes = 16 + words * 8 + padded8(marked * 2) + padded8(fragments * sizeof(Fragment));
    growTo(out, offset + bytes);
    uint8_t* p = out.data() + offset;
    std::memcpy(p, &marked, 8);
    std::memcpy(p + 8, &fragments, 8);
    p += 16;
    std::memcpy(p, region.words.data() + start.word, words * 8);
    p += words * 8;
    std::memcpy(p, region.counts.data() + start.marked, marked * 2);
    std::memset(p + marked * 2, 0, padded8(marked * 2) - marked * 2);
    p += padded8(marked * 2);
    std::memcpy(p, region.fragments.data() + start.fragments, fragments * sizeof(Fragment));
    std::memset(p + fragments * sizeof(Fragment), 0, padded8(fragments * sizeof(Fragment)) - fragments * sizeof(Fragment));
    return bytes;
}

// A received part of `pixels` pixels, checked against its length.
PartView parsePart(const uint8_t* bytes, uint64_t length, uint64_t pixels, int sender) {
    PartView view;
    view.wordCount = wordsFor(pixels);
    const auto fail = [&] {
        throw std::runtime_error("Compositor: rank " + std::to_string(sender) + " sent a malformed part of " +
                                 std::to_string(length) + " bytes for " + std::to_string(pixels) + " pixels");
    };
    if (length < 16) fail();
    const auto marked = load<uint64_t>(bytes), fragments = load<uint64_t>(bytes + 8);
    if (marked > pixels || fragments > (length / sizeof(Fragment)) ||
        16 + view.wordCount * 8 + padded8(marked * 2) + padded8(fragments * sizeof(Fragment)) != length)
        fail();
    view.marked = marked;
    view.fragmentCount = fragments;
    view.words = bytes + 16;
    // The mask must mark exactly `marked` pixels, none past the part's end (walkParts reads a count for
    // each marked pixel).
    uint64_t bits = 0;
    for (uint64_t w = 0; w < view.wordCount; ++w) bits += uint64_t(std::popcount(view.word(w)));
    const uint64_t tail = pixels % kPixelsPerWord;
    if (bits != marked || (tail != 0 && (view.word(view.wordCount - 1) >> tail) != 0)) fail();
    view.counts = view.words + view.wordCount * 8;
    view.fragments = view.counts + padded8(marked * 2);
    return view;
}

// Own data of a part as a view (no copy).
PartView ownPart(const DeepRegion& region, uint64_t begin, uint64_t end, Cursor& at) {
    advanceTo(region, firstWord(region, begin), at);
    Cursor last = at;
    advanceTo(region, endWord(region, end), last);
    PartView view;
    view.wordCount = last.word - at.word;
    view.marked = last.marked - at.marked;
    view.fragmentCount = last.fragments - at.fragments;
    view.words = reinterpret_cast<const uint8_t*>(region.words.data() + at.word);
    view.counts = reinterpret_cast<const uint8_t*>(region.counts.data() + at.marked);
    view.fragments = reinterpret_cast<const uint8_t*>(region.fragments.data() + at.fragments);
    return view;
}

// Walks the pixels of a part that any source marks, in order: onWord(w, mask) for each word of the merged
// mask, then onPixel(p, fragments, n) with each marked pixel (p: its index in the part) and its fragments
// from every source, in source order.
template <class OnWord, class OnPixel>
void walkParts(const std::vector<PartView>& sources, uint64_t count, OnWord onWord, OnPixel onPixel) {
    struct Source {
        const uint8_t* counts;
        const uint8_t* fragments;
        const uint8_t* fragmentsEnd;
        uint64_t word;
    };
    std::vector<Source> cursor;
    // One fragment per marked pixel in every source (always in the first round, so at 2 ranks): each
    // pixel's fragments are gathered without a branch per source.
    bool oneEach = true;
    for (const PartView& v : sources) {
        cursor.push_back({v.counts, v.fragments, v.fragments + v.fragmentCount * sizeof(Fragment), 0});
        oneEach = oneEach && v.fragmentCount == v.marked;
    }
    std::vector<Fragment> pixel(sources.size());
    static constexpr Fragment unused{};  // read, never kept, when a source does not mark the pixel
    for (uint64_t w = 0; w < wordsFor(count); ++w) {
        uint64_t any = 0;
        for (size_t s = 0; s < sources.size(); ++s) any |= cursor[s].word = sources[s].word(w);
        onWord(w, any);
        for (uint64_t bits = any; bits != 0; bits &= bits - 1) {
            const int bit = std::countr_zero(bits);
            size_t n = 0;
            if (oneEach) {
                for (Source& source : cursor) {
                    const uint64_t marks = (source.word >> bit) & 1u;
                    const uint8_t* from = select(marks, source.fragments, reinterpret_cast<const uint8_t*>(&unused));
                    std::memcpy(pixel.data() + n, from, sizeof(Fragment));
                    n += marks;
                    source.fragments += marks * sizeof(Fragment);
                }
                onPixel(w * kPixelsPerWord + uint64_t(bit), pixel.data(), n);
                continue;
            }
            for (Source& source : cursor) {
                if (!((source.word >> bit) & 1u)) continue;
                const auto k = load<uint16_t>(source.counts);
                source.counts += 2;
                const size_t bytes = size_t(k) * sizeof(Fragment);
                if (bytes > size_t(source.fragmentsEnd - source.fragments))
                    throw std::runtime_error("Compositor: a part's counts exceed its fragments");
                if (n + k > pixel.size()) pixel.resize(n + k);
                if (k == 1) std::memcpy(pixel.data() + n, source.fragments, sizeof(Fragment));  // inlined
                else std::memcpy(pixel.data() + n, source.fragments, bytes);
                source.fragments += bytes;
                n += k;
            }
            if (n > UINT16_MAX) throw std::runtime_error("Compositor: more than 65535 fragments in one pixel");
            onPixel(w * kPixelsPerWord + uint64_t(bit), pixel.data(), n);
        }
    }
}

// Every source's fragments of [first, first + count), concatenated per pixel in source order.
void mergeParts(const std::vector<PartView>& sources, uint64_t first, uint64_t count, DeepRegion& out) {
    out.first = first;
    out.count = count;
    out.words.assign(wordsFor(count), 0);
    uint64_t fragmentBound = 0;
    for (const PartView& source : sources) fragmentBound += source.fragmentCount;
    growTo(out.counts, count);
    growTo(out.fragments, fragmentBound);
    out.marked = out.fragmentCount = 0;
    walkParts(sources, count, [&](uint64_t w, uint64_t mask) { out.words[w] = mask; },
              [&](uint64_t, const Fragment* pixel, size_t n) {
                  out.counts[out.marked++] = uint16_t(n);
                  std::copy(pixel, pixel + n, out.fragments.begin() + long(out.fragmentCount));
                  out.fragmentCount += n;
              });
}

// Front-to-back blend of one pixel's n >= 1 fragments, sorted by depth in place (stable: equal depths keep
// rank order), written as 4 floats of premultiplied color at `rgba` and a float at `depth`.
void blend(Fragment* pixel, size_t n, void* rgba, void* depth) {
    if (n == 1) {  // blending over nothing gives the fragment itself
        std::memcpy(rgba, pixel[0].rgba, 16);
        std::memcpy(depth, &pixel[0].depth, 4);
        return;
    }
    for (size_t a = 1; a < n; ++a)
        for (size_t b = a; b > 0 && pixel[b - 1].depth > pixel[b].depth; --b) std::swap(pixel[b - 1], pixel[b]);
    float color[4] = {0.0f, 0.0f, 0.0f, 0.0f}, nearest = INFINITY;
    for (const Fragment& f : std::span(pixel, n)) {
        const float transmitted = 1.0f - color[3];
        for (int c = 0; c < 4; ++c) color[c] += transmitted * f.rgba[c];
        nearest = std::min(nearest, f.depth);
    }
    std::memcpy(rgba, color, 16);
    std::memcpy(depth, &nearest, 4);
}

// The last round: every source's fragments of a part of `count` pixels blended, as the message to rank 0
// (the merged mask, then one blended fragment per marked pixel) at the start of `out` (grown as needed).
// Returns its bytes.
uint64_t blendParts(const std::vector<PartView>& sources, uint64_t count, std::vector<uint8_t>& out) {
    const uint64_t words = wordsFor(count);
    uint64_t marked = 0;
    for (uint64_t w = 0; w < words; ++w) {
        uint64_t any = 0;
        for (const PartView& source : sources) any |= source.word(w);
        marked += uint64_t(std::popcount(any));
    }
    const uint64_t bytes = words * 8 + marked * sizeof(Fragment);
    growTo(out, bytes);
    uint8_t* fragment = out.data() + words * 8;
    walkParts(sources, count, [&](uint64_t w, uint64_t mask) { std::memcpy(out.data() + w * 8, &mask, 8); },
              [&](uint64_t, Fragment* pixel, size_t n) {
                  blend(pixel, n, fragment, fragment + 16);
                  fragment += sizeof(Fragment);
              });
    return bytes;
}

// The last round on rank 0: its part blended straight into the image (`rgba` and `depth` at the part's
// first pixel), background (0, +infinity) where no source marks a pixel.
void blendInto(const std::vector<PartView>& sources, uint64_t count, float* rgba, float* depth) {
    walkParts(sources, count,
              [&](uint64_t w, uint64_t) {
                  const uint64_t first = w * kPixelsPerWord, last = std::min(count, first + kPixelsPerWord);
                  std::fill(rgba + first * 4, rgba + last * 4, 0.0f);
                  std::fill(depth + first, depth + last, INFINITY);
              },
              [&](uint64_t p, Fragment* pixel, size_t n) {
                  blend(pixel, n, rgba + p * 4, depth + p);
              });
}

uint64_t markedIn(const uint8_t* words, uint64_t count) {
    uint64_t marked = 0;
    for (uint64_t w = 0; w < count; ++w) marked += uint64_t(std::popcount(load<uint64_t>(words + w * 8)));
    return marked;
}

}  // namespace

const char* compositeMethodName(CompositeMethod method) {
    switch (method) {
    case CompositeMethod::Auto: return "auto";
    case CompositeMethod::DirectSend: return "directSend";
    case CompositeMethod::BinarySwap: return "binarySwap";
    case CompositeMethod::RadixK: return "radixK";
    }
    return "unknown";
}

std::optional<CompositeMethod> parseCompositeMethod(std::string_view name) {
    for (CompositeMethod m : {CompositeMethod::Auto, CompositeMethod::DirectSend, CompositeMethod::BinarySwap,
                              CompositeMethod::RadixK})
        if (name == compositeMethodName(m)) return m;
    return std::nullopt;
}

std::vector<uint32_t> compositeRounds(uint32_t ranks, CompositeMethod method) {
    if (ranks <= 1) return {};
    switch (method) {
    case CompositeMethod::DirectSend: return {ranks};
    case CompositeMethod::BinarySwap: {
        if (!std::has_single_bit(ranks))
            throw std::invalid_argument("binary swap needs a power-of-two rank count, not " + std::to_string(ranks));
        return std::vector<uint32_t>(size_t(std::countr_zero(ranks)), 2u);
    }
    case CompositeMethod::Auto:
    case CompositeMethod::RadixK: break;
    }
    std::vector<uint32_t> primes;  // descending
    uint32_t rest = ranks;
    for (uint32_t p = 2; p * p <= rest; ++p)
        while (rest % p == 0) {
            primes.push_back(p);
            rest /= p;
        }
    if (rest > 1) primes.push_back(rest);
    std::sort(primes.rbegin(), primes.rend());
    std::vector<uint32_t> groups;  // first fit: each prime joins the first group it keeps within kMaxRadix
    for (uint32_t p : primes) {
        auto fits = std::find_if(groups.begin(), groups.end(), [&](uint32_t g) { return g * p <= kMaxRadix; });
        if (fits != groups.end()) *fits *= p;
        else groups.push_back(p);
    }
    std::sort(groups.rbegin(), groups.rend());
    return groups;
}

Compositor::Compositor(Communicator ranks, CompositeMethod method) : ranks_(std::move(ranks)) {
    // Ranks with other rounds would wait for each other forever: every rank checks that all chose alike
    // (before anything can throw on one rank alone).
    const uint64_t mine[] = {uint64_t(method)};
    uint64_t lowest[1] = {}, highest[1] = {};
    ranks_.minMax(mine, lowest, highest);
    if (lowest[0] != highest[0])
        throw std::invalid_argument("the ranks chose different compositing methods (every rank must set the same)");
    rounds_ = compositeRounds(uint32_t(ranks_.size()), method);  // throws on every rank alike
}

void Compositor::resize(uint32_t width, uint32_t height) {
    width_ = width;
    height_ = height;
    rgba_.clear();
    depth_.clear();
}

void Compositor::composite(std::span<const float> rgba, std::span<const float> depth) {
    const uint64_t pixels = uint64_t(width_) * height_;
    if (rgba.size() != pixels * 4 || depth.size() != pixels)
        throw std::invalid_argument("Compositor: an image of " + std::to_string(rgba.size() / 4) + " pixels and " +
                                    std::to_string(depth.size()) + " depths for a " + std::to_string(width_) + "x" +
                                    std::to_string(height_) + " frame");
    bytesSent_ = fragmentsSent_ = 0;
    if (!ranks_.distributed()) {  // one rank: its image is the whole image
        rgba_.assign(rgba.begin(), rgba.end());
        depth_.assign(depth.begin(), depth.end());
        return;
    }
    const auto rank = uint32_t(ranks_.rank()), rankCount = uint32_t(ranks_.size());

    // This rank's fragments: its surfaces, and on rank 0 the background where it is not transparent.
    const bool keepBackground = rank == 0;
    mine_.first = 0;
    mine_.count = pixels;
    mine_.words.assign(wordsFor(pixels), 0);
    growTo(mine_.counts, pixels);
    growTo(mine_.fragments, pixels);
    uint64_t marked = 0;
    for (uint64_t w = 0; w < mine_.words.size(); ++w) {
        const uint64_t first = w * kPixelsPerWord, last = std::min(pixels, first + kPixelsPerWord);
        uint8_t kept[kPixelsPerWord] = {};
        const float* d = depth.data() + first;
        for (uint64_t i = 0; i < last - first; ++i) kept[i] = std::fabs(d[i]) != INFINITY;
        if (keepBackground)
            for (uint64_t i = 0; i < last - first; ++i) kept[i] |= rgba[(first + i) * 4 + 3] != 0.0f;
        const uint64_t mask = packBits(kept);
        mine_.words[w] = mask;
        for (uint64_t bits = mask; bits != 0; bits &= bits - 1) {  // only what travels is copied
            const uint64_t p = first + uint64_t(std::countr_zero(bits));
            std::memcpy(mine_.fragments[marked].rgba, rgba.data() + p * 4, 16);
            mine_.fragments[marked++].depth = depth[p];
        }
    }
    std::fill(mine_.counts.begin(), mine_.counts.begin() + long(marked), uint16_t(1));
    mine_.marked = mine_.fragmentCount = marked;

    uint32_t stride = 1;
    uint64_t blendedBytes = 0;
    for (uint32_t k : rounds_) {
        const uint32_t digit = rank / stride % k;
        const uint32_t base = rank - digit * stride;
        // Send each member the part it keeps (nothing to ranks outside the group).
        sendCounts_.assign(rankCount, 0);
        uint64_t sendBytes = 0;
        Cursor at;
        for (uint32_t j = 0; j < k; ++j) {
            const uint32_t member = base + j * stride;
            const uint64_t begin = partBegin(mine_.first, mine_.count, j, k), end = partBegin(mine_.first, mine_.count, j + 1, k);
            if (member == rank) continue;
            sendCounts_[member] = writePart(mine_, begin, end, at, send_, sendBytes);
            fragmentsSent_ += load<uint64_t>(send_.data() + sendBytes + 8);  // the part's header
            sendBytes += sendCounts_[member];
            bytesSent_ += sendCounts_[member];
        }
        ranks_.alltoallv(std::span(send_).first(sendBytes), sendCounts_, received_, receivedOffsets_);
        // Merge every member's fragments of the part this rank keeps, in member (= rank) order.
        const uint64_t keepBegin = partBegin(mine_.first, mine_.count, digit, k);
        const uint64_t keepEnd = partBegin(mine_.first, mine_.count, digit + 1, k);
        std::vector<PartView> sources;
        Cursor own;
        for (uint32_t j = 0; j < k; ++j) {
            const uint32_t member = base + j * stride;
            if (member == rank) {
                sources.push_back(ownPart(mine_, keepBegin, keepEnd, own));
                continue;
            }
            const uint64_t from = receivedOffsets_[member], length = receivedOffsets_[member + 1] - from;
            sources.push_back(parsePart(received_.data() + from, length, keepEnd - keepBegin, int(member)));
        }
        for (uint32_t r = 0; r < rankCount; ++r)  // nobody outside the group may send here
            if ((r < base || (r - base) % stride != 0 || (r - base) / stride >= k) &&
                receivedOffsets_[r + 1] != receivedOffsets_[r])
                throw std::runtime_error("Compositor: rank " + std::to_string(r) + " sent to a rank outside its group");
        stride *= k;
        if (stride == rankCount) {  // the last round: blend into the message to rank 0 (on it, the image)
            if (rank == 0) {
                rgba_.resize(pixels * 4);
                depth_.resize(pixels);
                blendInto(sources, keepEnd - keepBegin, rgba_.data() + keepBegin * 4, depth_.data() + keepBegin);
            } else {
                blendedBytes = blendParts(sources, keepEnd - keepBegin, send_);
            }
            break;
        }
        mergeParts(sources, keepBegin, keepEnd - keepBegin, merged_);
        std::swap(mine_, merged_);
    }

    if (rank != 0) bytesSent_ += blendedBytes;
    ranks_.gatherToRoot(std::span(send_).first(blendedBytes), received_, receivedOffsets_);
    if (rank != 0) return;

    // Every pixel lies in one rank's region and is written once: blended, or background (0, +infinity);
    // rank 0's own region already is.
    static constexpr Fragment background{{0.0f, 0.0f, 0.0f, 0.0f}, INFINITY};
    for (uint32_t r = 1; r < rankCount; ++r) {
        const Span region = finalRegion(r, pixels, rounds_);
        const uint8_t* bytes = received_.data() + receivedOffsets_[r];
        const uint64_t length = receivedOffsets_[r + 1] - receivedOffsets_[r], regionWords = wordsFor(region.count);
        if (length < regionWords * 8 || (length - regionWords * 8) % sizeof(Fragment) != 0)
            throw std::runtime_error("Compositor: rank " + std::to_string(r) + " sent a malformed region");
        const uint8_t* fragment = bytes + regionWords * 8;
        if ((length - regionWords * 8) / sizeof(Fragment) != markedIn(bytes, regionWords))
            throw std::runtime_error("Compositor: rank " + std::to_string(r) + " sent a malformed region");
        for (uint64_t w = 0; w < regionWords; ++w) {
            const uint64_t bits = load<uint64_t>(bytes + w * 8);
            const uint64_t first = region.first + w * kPixelsPerWord;
            const uint64_t last = std::min(region.first + region.count, first + kPixelsPerWord);
            for (uint64_t p = first; p < last; ++p) {
                const uint64_t marks = (bits >> (p - first)) & 1u;
                const auto f = load<Fragment>(select(marks, fragment, reinterpret_cast<const uint8_t*>(&background)));
                fragment += marks * sizeof(Fragment);
                std::memcpy(rgba_.data() + p * 4, f.rgba, 16);
                depth_[p] = f.depth;
            }
        }
    }
}

}  // namespace ripple::mpi
