// Gathering and printing --stats (see RankStats.h). Plain bytes travel: every rank runs this same program.
#include "apps/ripple-render/RankStats.h"

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
}

}  // namespace ripple::apps
