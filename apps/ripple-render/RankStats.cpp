// Gathering and printing --stats (see RankStats.h). Plain bytes travel: every rank runs this same program.
#include "apps/ripple-render/RankStats.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace ripple::apps {

static_assert(std::is_trivially_copyable_v<RankStats>);

void printRankStats(const mpi::Communicator& ranks, const RankStats& mine) {
    const auto bytes = std::span(reinterpret_cast<const uint8_t*>(&mine), sizeof mine);
    const std::vector<std::vector<uint8_t>> all = ranks.gatherToRoot(bytes);
    if (ranks.rank() != 0) return;
    std::printf("%5s %12s %12s %16s %16s\n", "rank", "triangles", "scene MiB", "rays sent/frame", "MiB sent/frame");
    for (size_t r = 0; r < all.size(); ++r) {
        RankStats s;
        if (all[r].size() != sizeof s) continue;
        std::memcpy(&s, all[r].data(), sizeof s);
        const double frames = s.frames > 0 ? double(s.frames) : 1.0;
        std::printf("%5zu %12llu %12.2f %16.0f %16.2f\n", r, static_cast<unsigned long long>(s.triangles),
                    double(s.sceneBytes) / 1048576.0, double(s.raysSent) / frames,
                    double(s.bytesSent) / frames / 1048576.0);
    }
    for (size_t r = 0; r < all.size(); ++r) {
        RankStats s;
        if (all[r].size() != sizeof s) continue;
        std::memcpy(&s, all[r].data(), sizeof s);
        std::vector<size_t> order(core::kStageCount);
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return s.stageMicroseconds[a] > s.stageMicroseconds[b]; });
        uint64_t total = 0;
        for (uint64_t t : s.stageMicroseconds) total += t;
        if (total == 0) continue;  // a device without the stage properties
        const double frames = s.stageFrames > 0 ? double(s.stageFrames) : 1.0;
        std::printf("rank %zu GPU time per frame after the first, %.1f ms:", r, double(total) / frames * 1e-3);
        for (size_t i : order)
            if (s.stageMicroseconds[i] > 0)
                std::printf(" %s %.1f (%.0f%%)", core::stageName(core::Stage(i)), double(s.stageMicroseconds[i]) / frames * 1e-3,
                            100.0 * double(s.stageMicroseconds[i]) / double(total));
        std::printf("\n");
    }
}

}  // namespace ripple::apps
