// Deep compositing of every rank's RGBA-z image by parallel direct send: the image each rank renders of its
// own share of the world becomes, on rank 0, the image of the whole world (no cross-rank light).
#pragma once

#include "mpi/Communicator.h"

#include <cstdint>
#include <span>
#include <vector>

namespace ripple::mpi {

// Alpha convention: colors are PREMULTIPLIED by alpha, and a fragment in front of another blends as
// front + (1 - front.alpha) * back. A pixel with depth +infinity is background: only rank 0's background
// is kept (every rank sees the same background), and it sorts behind every surface. Ranks with empty
// worlds send only background, so they contribute nothing.
class Compositor {
public:
    explicit Compositor(Communicator ranks);

    void resize(uint32_t width, uint32_t height);
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

    // Collective. rgba: width*height*4 floats (premultiplied), depth: width*height floats, rows in order.
    void composite(std::span<const float> rgba, std::span<const float> depth);

    // The whole composited image on rank 0 (empty on other ranks); depth is the nearest fragment's.
    const std::vector<float>& rgba() const { return rgba_; }
    const std::vector<float>& depth() const { return depth_; }
    // Bytes this rank sent to other ranks in the last composite (fragments, and its band to rank 0).
    uint64_t bytesSent() const { return bytesSent_; }
    const Communicator& ranks() const { return ranks_; }

private:
    uint32_t bandBegin(int rank) const;  // first row of the band rank owns

    Communicator ranks_;
    uint32_t width_ = 0, height_ = 0;
    std::vector<float> rgba_, depth_;
    uint64_t bytesSent_ = 0;
    // Working buffers of composite(), kept between frames.
    std::vector<std::vector<uint8_t>> outgoing_;
    std::vector<uint32_t> starts_, cursor_;
    std::vector<uint8_t> band_;
};

}  // namespace ripple::mpi
