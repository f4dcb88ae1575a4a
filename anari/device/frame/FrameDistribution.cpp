// A frame rendered by one rank alone, and the choice between it and the data-parallel distribution (see
// FrameDistribution.h).
#include "anari/device/frame/FrameDistribution.h"

#include "anari/device/frame/DataParallelFrame.h"
#include "anari/device/scene/SceneSync.h"

namespace ripple::device {
namespace {

class SingleRankFrame final : public FrameDistribution {
public:
    std::string disagreement(const FrameFingerprint&) override { return {}; }
    bool shareLights(SceneSync&, World&, bool restart) override { return restart; }
    bool anyRank(bool value) override { return value; }
    bool rendersOnWorker() const override { return true; }
    core::RayExchange* exchange(core::ExchangeKind) override { return nullptr; }
    const core::Scene& scene(SceneSync& sync, const vk::Context& context, bool& rebuilt) override {
        return sync.scene(context, rebuilt);
    }
    void gather(glm::uvec2, size_t, void*) override {}
    void failed(const std::string&) override {}
};

}  // namespace

uint64_t fingerprintHash(const void* bytes, size_t size, uint64_t hash) {
    const auto* byte = static_cast<const uint8_t*>(bytes);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ byte[i]) * 0x100000001b3ull;
    return hash;
}

std::unique_ptr<FrameDistribution> makeFrameDistribution(const mpi::Communicator& ranks) {
    if (ranks.distributed()) return std::make_unique<DataParallelFrame>(ranks);
    return std::make_unique<SingleRankFrame>();
}

}  // namespace ripple::device
