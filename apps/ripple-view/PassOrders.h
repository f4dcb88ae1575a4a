// ripple-view under mpirun: rank 0 owns the window and decides every pass; before each it sends the other
// ranks a PassOrder (the view, settings and sizes that changed, and which frame to render), so that every
// rank commits the same objects and enters the same collective render. The others open no window. A
// data-parallel frame renders on the thread that calls anariRenderFrame, so rank 0's window waits for each
// pass (and MPI is never called from two threads at once).
#pragma once

#include "apps/ripple-view/ProgressiveFrames.h"
#include "apps/ripple-view/ScenePanels.h"
#include "mpi/Communicator.h"

#include <cstdint>
#include <vector>

namespace ripple::apps {

struct PassOrder {
    bool quit = false;                  // the viewer is closing: no more passes
    bool moving = false;                // the reduced frame (startPass's `moving`); rank 0 decided the pass is due
    PendingChanges changes;             // taken up before the pass (ProgressiveFrames::apply)
    // Edited volumes and iso-surfaces (encodeFieldEdits), committed before the pass: every rank holds its
    // own slab of each. Lights need no order: rank 0 alone holds them.
    std::vector<uint8_t> fieldEdits;
};

// Rank 0's `order` on every rank. Collective.
PassOrder sharePassOrder(const mpi::Communicator& ranks, const PassOrder& order);
// The order's fixed part as broadcast (everything but fieldEdits, whose size it holds), and back.
std::vector<uint8_t> encodePassOrder(const PassOrder& order);
PassOrder decodePassOrder(const std::vector<uint8_t>& bytes);

// The values of the volumes and iso-surfaces `requests` names, as rank 0 edited them.
std::vector<uint8_t> encodeFieldEdits(const SceneEdits& edits, const SceneEditRequests& requests);
// Writes encoded values into this rank's records (the same scene, so the same lists) and returns which to
// commit. Throws when they do not fit the lists.
SceneEditRequests decodeFieldEdits(const std::vector<uint8_t>& bytes, SceneEdits& edits);

// Whether rank 0 got through what can fail before rendering (its options, its window): the other ranks
// wait for this before they open the device, and end with rank 0 when it could not start. Collective;
// rank 0's `started` is the answer (the others' is not read).
bool shareStart(const mpi::Communicator& ranks, bool started);

}  // namespace ripple::apps
