// Parallel direct send (see Compositor.h): rank r owns rows [bandBegin(r), bandBegin(r + 1)); every rank
// sends each owner the fragments of its rows in one MPI_Alltoallv, owners blend, rank 0 gathers the bands.
#include "mpi/Compositor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ripple::mpi {

namespace {

struct Fragment {
    uint32_t pixel;  // index inside the receiving rank's band
    float rgba[4];
    float depth;
};
static_assert(sizeof(Fragment) == 24);

struct BandPixel {
    float rgba[4];
    float depth;
};

}  // namespace

Compositor::Compositor(Communicator ranks) : ranks_(std::move(ranks)) {}

void Compositor::resize(uint32_t width, uint32_t height) {
    width_ = width;
    height_ = height;
    rgba_.clear();
    depth_.clear();
}

uint32_t Compositor::bandBegin(int rank) const {
    return uint32_t(uint64_t(height_) * uint64_t(rank) / uint64_t(ranks_.size()));
}

void Compositor::composite(std::span<const float> rgba, std::span<const float> depth) {
    const size_t pixels = size_t(width_) * height_;
    if (rgba.size() != pixels * 4 || depth.size() != pixels)
        throw std::invalid_argument("Compositor: an image of " + std::to_string(rgba.size() / 4) + " pixels and " +
                                    std::to_string(depth.size()) + " depths for a " + std::to_string(width_) + "x" +
                                    std::to_string(height_) + " frame");
    bytesSent_ = 0;
    if (!ranks_.distributed()) {  // one rank: its image is the whole image
        rgba_.assign(rgba.begin(), rgba.end());
        depth_.assign(depth.begin(), depth.end());
        return;
    }
    const int rankCount = ranks_.size();
    const bool keepBackground = ranks_.rank() == 0;
    auto sent = [&](size_t p) { return !std::isinf(depth[p]) || (keepBackground && rgba[p * 4 + 3] != 0.0f); };
    // Counted first, so each owner's buffer is written in place at its final size; the buffers are kept
    // from frame to frame, so a steady frame allocates (and page-faults) nothing for them.
    outgoing_.resize(static_cast<size_t>(rankCount));
    for (int owner = 0; owner < rankCount; ++owner) {
        const size_t first = size_t(bandBegin(owner)) * width_, last = size_t(bandBegin(owner + 1)) * width_;
        size_t count = 0;
        for (size_t p = first; p < last; ++p) count += sent(p);
        std::vector<uint8_t>& bytes = outgoing_[size_t(owner)];
        bytes.resize(count * sizeof(Fragment));
        uint8_t* out = bytes.data();
        for (size_t p = first; p < last; ++p) {
            if (!sent(p)) continue;
            const Fragment fragment{uint32_t(p - first), {rgba[p * 4], rgba[p * 4 + 1], rgba[p * 4 + 2], rgba[p * 4 + 3]},
                                    depth[p]};
            std::memcpy(out, &fragment, sizeof(Fragment));
            out += sizeof(Fragment);
        }
        if (owner != ranks_.rank()) bytesSent_ += bytes.size();  // what stays on this rank crosses nothing
    }
    const std::vector<std::vector<uint8_t>> received = ranks_.alltoallv(outgoing_);

    // Bucket the fragments by pixel (counting sort, senders in rank order), then order each pixel's by
    // depth with a stable insertion sort (a pixel has at most one fragment per rank); equal depths keep
    // rank order, so the result does not depend on MPI's arrival order.
    const size_t bandPixels = size_t(bandBegin(ranks_.rank() + 1) - bandBegin(ranks_.rank())) * width_;
    std::vector<uint32_t>& starts = starts_;
    starts.assign(bandPixels + 1, 0);
    size_t total = 0;
    for (const std::vector<uint8_t>& bytes : received) {
        for (size_t at = 0; at + sizeof(Fragment) <= bytes.size(); at += sizeof(Fragment)) {
            uint32_t pixel;
            std::memcpy(&pixel, bytes.data() + at, sizeof(pixel));
            if (pixel >= bandPixels) throw std::runtime_error("Compositor: a fragment outside the band");
            ++starts[pixel + 1];
            ++total;
        }
    }
    for (size_t p = 0; p < bandPixels; ++p) starts[p + 1] += starts[p];
    std::vector<Fragment> byPixel(total);
    std::vector<uint32_t>& cursor = cursor_;
    cursor.assign(starts.begin(), starts.end() - 1);
    for (const std::vector<uint8_t>& bytes : received) {
        for (size_t at = 0; at + sizeof(Fragment) <= bytes.size(); at += sizeof(Fragment)) {
            Fragment fragment;
            std::memcpy(&fragment, bytes.data() + at, sizeof(Fragment));
            byPixel[cursor[fragment.pixel]++] = fragment;
        }
    }

    std::vector<uint8_t>& band = band_;
    band.resize(bandPixels * sizeof(BandPixel));
    for (size_t p = 0; p < bandPixels; ++p) {
        Fragment* begin = byPixel.data() + starts[p];
        Fragment* end = byPixel.data() + starts[p + 1];
        for (Fragment* it = begin + 1; it < end; ++it)  // stable: moves a fragment only past deeper ones
            for (Fragment* j = it; j > begin && (j - 1)->depth > j->depth; --j) std::swap(*(j - 1), *j);
        BandPixel out{{0.0f, 0.0f, 0.0f, 0.0f}, INFINITY};
        for (const Fragment* it = begin; it != end; ++it) {
            const float transmitted = 1.0f - out.rgba[3];
            for (int c = 0; c < 4; ++c) out.rgba[c] += transmitted * it->rgba[c];
            out.depth = std::min(out.depth, it->depth);
        }
        std::memcpy(band.data() + p * sizeof(BandPixel), &out, sizeof(BandPixel));
    }
    if (ranks_.rank() != 0) bytesSent_ += band.size();

    const std::vector<std::vector<uint8_t>> bands = ranks_.gatherToRoot(band);
    if (ranks_.rank() != 0) return;
    rgba_.assign(pixels * 4, 0.0f);
    depth_.assign(pixels, INFINITY);
    for (int owner = 0; owner < rankCount; ++owner) {
        const size_t first = size_t(bandBegin(owner)) * width_;
        const std::vector<uint8_t>& bytes = bands[size_t(owner)];
        for (size_t i = 0; i * sizeof(BandPixel) < bytes.size(); ++i) {
            BandPixel pixel;
            std::memcpy(&pixel, bytes.data() + i * sizeof(BandPixel), sizeof(BandPixel));
            std::copy(pixel.rgba, pixel.rgba + 4, rgba_.begin() + long((first + i) * 4));
            depth_[first + i] = pixel.depth;
        }
    }
}

}  // namespace ripple::mpi
