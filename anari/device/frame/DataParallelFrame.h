// Data-parallel ANARI at anariRenderFrame, which is collective: the ranks check with one reduction that
// they render the same frame (creation order), world, size, channels, camera and renderer, and a rank that
// cannot render says so to all; lights of every rank are gathered, the world's radius reduced, and an
// accumulation restart on any rank restarts it on all. Rank 0 assembles the image.
#pragma once

#include "anari/device/frame/FrameDistribution.h"
#include "mpi/BoundsExchange.h"
#include "mpi/RingExchange.h"

#include <vector>

namespace ripple::device {

class DataParallelFrame final : public FrameDistribution {
public:
    explicit DataParallelFrame(const mpi::Communicator& ranks);

    std::string disagreement(const FrameFingerprint& mine) override;
    bool shareLights(SceneSync& sync, World& world, bool restart) override;
    bool anyRank(bool value) override { return ranks_.max(value ? 1 : 0) > 0; }
    bool rendersOnWorker() const override { return false; }
    core::RayExchange* exchange(core::ExchangeKind kind) override;
    const core::Scene& scene(SceneSync& sync, const vk::Context& context, bool& rebuilt) override;
    void gather(glm::uvec2 size, size_t bytesPerPixel, void* pixels) override;
    std::string whyCannotGather(glm::uvec2 size, uint64_t bytesPerPixel) const override;
    [[noreturn]] void failed(const std::string& message) override;

private:
    mpi::Communicator ranks_;
    mpi::RingExchange ring_;
    mpi::BoundsExchange bounds_;
};

// The message for fingerprints that differ (indexed by rank; the same on every rank): the first rank that
// cannot render, else the first field in which a rank differs from rank 0.
std::string describeDisagreement(const std::vector<FrameFingerprint>& ranks);

}  // namespace ripple::device
