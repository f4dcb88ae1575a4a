// ripple-render's run once its options are parsed: the plan checked from the options, the device opened,
// the scene built, frames rendered with progress and the error estimate, and every output written.
#pragma once

#include "apps/ripple-render/Options.h"
#include "apps/ripple-render/TimeBudget.h"
#include "apps/scene/AnariSession.h"
#include "mpi/Communicator.h"

namespace ripple::apps {

// Renders what `options` ask for on this rank; rank 0 writes the outputs. Returns the exit code; throws
// std::runtime_error for what stops the run (a file that cannot be read or written, a device that fails).
int render(const Options& options, const mpi::Communicator& ranks, Session& s, TimeBudget& budget);

}  // namespace ripple::apps
