// ripple-view under mpirun: rank 0 owns the window and decides every pass; before each it sends the other
// ranks a PassOrder (the view, settings and sizes that changed, and which frame to render), so that every
// rank commits the same objects and enters the same collective render. The others open no window.
#pragma once

#include "apps/ripple-view/ProgressiveFrames.h"
#include "apps/ripple-view/ScenePanels.h"
#include "mpi/Communicator.h"

#include <cstdint>
#include <vector>

namespace ripple::apps {

struct PassOrder {
    bool quit = false;                  // the viewer is closing: no more passes
    bool moving = false;                // startPass's arguments
    uint32_t maxSamples = 0;
    PendingChanges changes;             // taken up before the pass (ProgressiveFrames::apply)
    // Edited volumes and iso-surfaces (encodeFieldEdits), committed before the pass: every rank holds its
    // own slab of each. Lights need no order: rank 0 alone holds them.
    std::vector<uint8_t> fieldEdits;
};

// Rank 0's `order` on every rank. Collective.
PassOrder sharePassOrder(const mpi::Communicator& ranks, const PassOrder& order);

// The values of the volumes and iso-surfaces `requests` names, as rank 0 edited them.
std::vector<uint8_t> encodeFieldEdits(const SceneEdits& edits, const SceneEditRequests& requests);
// Writes encoded values into this rank's records (the same scene, so the same lists) and returns which to
// commit. Throws when they do not fit the lists.
SceneEditRequests decodeFieldEdits(const std::vector<uint8_t>& bytes, SceneEdits& edits);

// Whether rank 0 got through what can fail before rendering (its options, its window): the other ranks
// wait for this before they open the device, and end with rank 0 when it could not start. Collective.
bool shareStart(const mpi::Communicator& ranks, bool started);

}  // namespace ripple::apps
