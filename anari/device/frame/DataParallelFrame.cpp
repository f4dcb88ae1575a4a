// Agreement across ranks (see DataParallelFrame.h): every rank gathers every rank's identity, so all of
// them reach the same verdict and either all render or none does (no rank waits for a collective the
// others skipped).
#include "anari/device/frame/DataParallelFrame.h"

#include "anari/device/scene/SceneSync.h"
#include "mpi/LightGather.h"

#include <cstring>
#include <type_traits>
#include <vector>

namespace ripple::device {

static_assert(std::is_trivially_copyable_v<FrameIdentity>);

std::string ranksDisagree(const mpi::Communicator& ranks, const FrameIdentity& mine) {
    FrameIdentity zeroed;
    std::memset(static_cast<void*>(&zeroed), 0, sizeof(zeroed));  // padding compares equal
    zeroed.frameIndex = mine.frameIndex;
    zeroed.worldIndex = mine.worldIndex;
    zeroed.size = mine.size;
    zeroed.renderable = mine.renderable;
    zeroed.pixelSamples = mine.pixelSamples;
    zeroed.maxPathLength = mine.maxPathLength;
    zeroed.camera = mine.camera;
    const auto bytes = std::span(reinterpret_cast<const uint8_t*>(&zeroed), sizeof(zeroed));
    const std::vector<std::vector<uint8_t>> all = ranks.allgather(bytes);
    std::vector<FrameIdentity> ids(all.size());
    for (size_t r = 0; r < all.size(); ++r) {
        if (all[r].size() != sizeof(FrameIdentity)) return "rank " + std::to_string(r) + " sent a malformed frame identity";
        std::memcpy(static_cast<void*>(&ids[r]), all[r].data(), sizeof(FrameIdentity));
    }
    for (size_t r = 0; r < ids.size(); ++r)
        if (!ids[r].renderable) return "rank " + std::to_string(r) + " cannot render this frame (see its messages)";
    const FrameIdentity& root = ids[0];
    for (size_t r = 1; r < ids.size(); ++r) {
        const FrameIdentity& other = ids[r];
        const std::string rank = "rank " + std::to_string(r);
        if (other.frameIndex != root.frameIndex)
            return rank + " renders its frame #" + std::to_string(other.frameIndex) + ", rank 0 its frame #" +
                   std::to_string(root.frameIndex) + ": every rank must create the same frames in the same order";
        if (other.worldIndex != root.worldIndex)
            return rank + " renders its world #" + std::to_string(other.worldIndex) + ", rank 0 its world #" +
                   std::to_string(root.worldIndex) + ": every rank must create the same worlds in the same order";
        if (other.size != root.size)
            return rank + "'s frame is " + std::to_string(other.size.x) + "x" + std::to_string(other.size.y) +
                   ", rank 0's " + std::to_string(root.size.x) + "x" + std::to_string(root.size.y);
        if (std::memcmp(&other.camera, &root.camera, sizeof(core::Camera)) != 0)
            return rank + "'s camera differs from rank 0's: every rank must set the same camera";
        if (other.pixelSamples != root.pixelSamples || other.maxPathLength != root.maxPathLength)
            return rank + "'s renderer differs from rank 0's (pixelSamples, maxPathLength)";
    }
    return {};
}

const core::Scene& sceneWithSharedEmitters(const mpi::Communicator& ranks, SceneSync& sync,
                                           const vk::Context& context, bool& rebuilt) {
    const core::Scene* scene = &sync.scene(context, rebuilt);
    if (ranks.max(rebuilt ? 1 : 0) == 0) return *scene;  // no emitter can have changed anywhere
    if (sync.setForeignTriangleLights(mpi::gatherForeignLightRecords(ranks, scene->triangleLights()))) {
        bool again = false;
        scene = &sync.scene(context, again);
        rebuilt = true;
    }
    return *scene;
}

}  // namespace ripple::device
