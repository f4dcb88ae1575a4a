// ripple-render --stats under mpirun: what each rank holds and sends, gathered and printed by rank 0.
#pragma once

#include "core/render/StageProfile.h"
#include "mpi/Communicator.h"

#include <cstdint>

namespace ripple::apps {

struct RankStats {
    uint64_t triangles = 0;    // triangles this rank's instances draw
    uint64_t sceneBytes = 0;   // GPU memory of its part of the scene (frame property ripple.sceneBytes)
    uint64_t raysSent = 0;     // summed over frames (frame property ripple.raysSent)
    uint64_t bytesSent = 0;
    uint64_t frames = 0;
    // GPU time of each stage of the wavefront loop (ripple.stageMicroseconds.NAME), summed over the
    // frames after the first (which includes compiling kernels on some drivers), and their count
    uint64_t stageMicroseconds[core::kStageCount] = {};
    uint64_t stageFrames = 0;
};

// Collective: rank 0 prints one line per rank (triangles, scene memory, rays and bytes sent per frame), then
// each rank's GPU time per frame by stage, the largest first.
void printRankStats(const mpi::Communicator& ranks, const RankStats& mine);

}  // namespace ripple::apps
