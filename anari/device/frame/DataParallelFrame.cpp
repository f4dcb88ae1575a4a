// Data-parallel distribution of a frame (see DataParallelFrame.h). Agreement costs one allreduce of the
// fingerprint's minimum and maximum; only when they differ are the fingerprints gathered, to name the rank
// and field. Every rank reaches the same verdict, so either all render or none does (no rank waits for a
// collective the others skipped).
#include "anari/device/frame/DataParallelFrame.h"

#include "anari/anari_type_traits.hpp"
#include "anari/device/scene/SceneSync.h"
#include "mpi/FrameGather.h"
#include "mpi/LightGather.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace ripple::device {
namespace {

std::string sizeText(uint64_t size) { return std::to_string(size >> 32) + "x" + std::to_string(size & 0xffffffffu); }

std::string channelsText(uint64_t channels) {
    const auto color = ANARIDataType(channels >> 32);
    std::string text = color == ANARI_UNKNOWN ? "no color" : std::string("color ") + ripple_anari::typeName(color);
    const char* const names[] = {"depth", "albedo", "normal", "primitiveId", "objectId", "instanceId"};
    const core::FrameChannels one[] = {{.depth = true},       {.albedo = true},   {.normal = true},
                                       {.primitiveId = true}, {.objectId = true}, {.instanceId = true}};
    for (size_t i = 0; i < 6; ++i)
        if (uint32_t(channels) & core::channelFeatures(one[i])) text += std::string(", ") + names[i];
    return text;
}

}  // namespace

DataParallelFrame::DataParallelFrame(const mpi::Communicator& ranks) : ranks_(ranks), ring_(ranks), bounds_(ranks) {}

core::RayExchange* DataParallelFrame::exchange(core::ExchangeKind kind) {
    if (kind == core::ExchangeKind::Ring) return &ring_;
    return &bounds_;
}

std::string describeDisagreement(const std::vector<FrameFingerprint>& ranks) {
    using F = FrameFingerprint;
    for (size_t r = 0; r < ranks.size(); ++r)
        if (!ranks[r].fields[F::Renderable])
            return "rank " + std::to_string(r) + " cannot render this frame (see its messages)";
    const auto& root = ranks.front().fields;
    for (size_t r = 1; r < ranks.size(); ++r) {
        const auto& other = ranks[r].fields;
        const std::string rank = "rank " + std::to_string(r);
        const auto differs = [&](F::Field f) { return other[f] != root[f]; };
        if (differs(F::FrameIndex))
            return rank + " renders its frame #" + std::to_string(other[F::FrameIndex]) + ", rank 0 its frame #" +
                   std::to_string(root[F::FrameIndex]) + ": every rank must create the same frames in the same order";
        if (differs(F::WorldIndex))
            return rank + " renders its world #" + std::to_string(other[F::WorldIndex]) + ", rank 0 its world #" +
                   std::to_string(root[F::WorldIndex]) + ": every rank must create the same worlds in the same order";
        if (differs(F::Size))
            return rank + "'s frame is " + sizeText(other[F::Size]) + ", rank 0's " + sizeText(root[F::Size]);
        if (differs(F::Channels))
            return rank + "'s frame has " + channelsText(other[F::Channels]) + ", rank 0's " +
                   channelsText(root[F::Channels]) + ": every rank must enable the same channels";
        if (differs(F::PixelSamples))
            return rank + "'s renderer has pixelSamples " + std::to_string(other[F::PixelSamples]) + ", rank 0's " +
                   std::to_string(root[F::PixelSamples]);
        if (differs(F::MaxPathLength))
            return rank + "'s renderer has maxPathLength " + std::to_string(other[F::MaxPathLength]) + ", rank 0's " +
                   std::to_string(root[F::MaxPathLength]);
        if (differs(F::Renderer))
            return rank + "'s renderer differs from rank 0's (subtype or parameters): every rank must set the same renderer";
        if (differs(F::RayExchange))
            return rank + " uses rayExchange '" + core::exchangeKindName(core::ExchangeKind(other[F::RayExchange])) +
                   "', rank 0 '" + core::exchangeKindName(core::ExchangeKind(root[F::RayExchange])) +
                   "': every rank must set the same device parameter rayExchange";
        if (differs(F::Camera))
            return rank + "'s camera differs from rank 0's: every rank must set the same camera";
    }
    return {};
}

std::string DataParallelFrame::disagreement(const FrameFingerprint& mine) {
    const mpi::Communicator& ranks = ranks_;
    std::array<uint64_t, FrameFingerprint::kFieldCount> lowest{}, highest{};
    ranks.minMax(mine.fields, lowest, highest);
    if (lowest == highest && lowest[FrameFingerprint::Renderable] == 1) return {};
    // Some field differs, or no rank can render: gather the fingerprints to say which rank and what.
    const auto bytes = std::span(reinterpret_cast<const uint8_t*>(mine.fields.data()), sizeof(mine.fields));
    const std::vector<std::vector<uint8_t>> all = ranks.allgather(bytes);
    std::vector<FrameFingerprint> fingerprints(all.size());
    for (size_t r = 0; r < all.size(); ++r) {
        if (all[r].size() != sizeof(mine.fields)) return "rank " + std::to_string(r) + " sent a malformed frame fingerprint";
        std::memcpy(fingerprints[r].fields.data(), all[r].data(), sizeof(mine.fields));
    }
    const std::string why = describeDisagreement(fingerprints);
    return why.empty() ? "the ranks' frames differ" : why;
}

bool DataParallelFrame::shareLights(SceneSync& sync, World& world, bool restart) {
    const mpi::Communicator& ranks = ranks_;
    bvh::Aabb bounds = worldBounds(world);
    ranks.min(std::span<float>(&bounds.lo.x, 3));
    ranks.max(std::span<float>(&bounds.hi.x, 3));
    const float radius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.hi - bounds.lo);
    const glm::vec3 largest = glm::max(glm::abs(bounds.lo), glm::abs(bounds.hi));
    const float magnitude = bounds.empty() ? 0.0f : std::max(largest.x, std::max(largest.y, largest.z));
    const bool lightsChanged = sync.setLights(mpi::gatherLights(ranks, sync.localLights()), radius, magnitude);
    return ranks.max((lightsChanged || restart) ? 1 : 0) > 0;
}

const core::Scene& DataParallelFrame::scene(SceneSync& sync, const vk::Context& context, bool& rebuilt) {
    const mpi::Communicator& ranks = ranks_;
    const core::Scene* scene = &sync.scene(context, rebuilt);
    if (ranks.max(rebuilt ? 1 : 0) == 0) return *scene;  // no emitter can have changed anywhere
    if (sync.setForeignTriangleLights(mpi::gatherForeignLightRecords(ranks, scene->triangleLights()))) {
        bool again = false;
        scene = &sync.scene(context, again);
        rebuilt = true;
    }
    return *scene;
}

void DataParallelFrame::gather(glm::uvec2 size, size_t bytesPerPixel, void* pixels) {
    mpi::gatherFrame(ranks_, size, bytesPerPixel, pixels);
}

std::string DataParallelFrame::whyCannotGather(glm::uvec2 size, uint64_t bytesPerPixel) const {
    // Rank 0 receives the whole channel in one MPI_Gatherv, whose counts and offsets are ints.
    const uint64_t bytes = uint64_t(size.x) * size.y * bytesPerPixel;  // sides of at most 16384 (commit): no overflow
    const uint64_t most = uint64_t(std::numeric_limits<int>::max());
    if (bytes <= most) return {};
    return "a data-parallel " + std::to_string(size.x) + "x" + std::to_string(size.y) + " channel of " +
           std::to_string(bytesPerPixel) + " bytes a pixel is more than one MPI gather carries to rank 0 (" +
           std::to_string(most) + " bytes); use a smaller size";
}

void DataParallelFrame::failed(const std::string& message) {
    ranks_.abort(message);
    std::abort();  // abort() returns only for one rank, which this distribution never has
}

}  // namespace ripple::device
