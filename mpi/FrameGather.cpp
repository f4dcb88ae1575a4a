// Gathering the owned bands (see FrameGather.h): each rank packs its bands back to back, rank 0 unpacks
// every rank's message with the same band assignment the ranks rendered with.
#include "mpi/FrameGather.h"

#include "core/render/PixelTiles.h"

#include <cstring>
#include <string>
#include <vector>

namespace ripple::mpi {

void gatherFrame(const Communicator& communicator, glm::uvec2 size, size_t bytesPerPixel, void* pixels) {
    if (!communicator.distributed()) return;
    auto* image = static_cast<uint8_t*>(pixels);
    const auto rangesOf = [&](int rank) {
        return core::ownedPixels(size, uint32_t(rank), uint32_t(communicator.size()));
    };
    std::vector<uint8_t> packed;
    for (const core::PixelRange& range : rangesOf(communicator.rank())) {
        const uint8_t* first = image + size_t(range.first) * bytesPerPixel;
        packed.insert(packed.end(), first, first + size_t(range.count) * bytesPerPixel);
    }
    const std::vector<std::vector<uint8_t>> parts = communicator.gatherToRoot(packed);
    if (communicator.rank() != 0) return;
    for (int rank = 1; rank < communicator.size(); ++rank) {
        const std::vector<uint8_t>& part = parts[size_t(rank)];
        size_t offset = 0;
        for (const core::PixelRange& range : rangesOf(rank)) {
            const size_t bytes = size_t(range.count) * bytesPerPixel;
            if (offset + bytes > part.size())
                throw MpiError("frame gather: rank " + std::to_string(rank) + " sent " + std::to_string(part.size()) +
                               " bytes, fewer than its pixels need (do the ranks agree on the frame size?)");
            std::memcpy(image + size_t(range.first) * bytesPerPixel, part.data() + offset, bytes);
            offset += bytes;
        }
    }
}

}  // namespace ripple::mpi
