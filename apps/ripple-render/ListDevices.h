// ripple-render --list-devices: the Vulkan devices the ANARI device sees, with the one it renders with
// marked, as the device reports them (its property "ripple.vulkanDevices"); under mpirun, every rank's.
#pragma once

#include "apps/ripple-render/Options.h"
#include "apps/scene/AnariSession.h"
#include "mpi/Communicator.h"

namespace ripple::apps {

// Prints the list to stdout (rank 0 prints every rank's, in rank order) and returns the exit code, 0.
// Throws std::runtime_error when the library cannot be loaded or its device does not list its devices.
int listDevices(const Options& options, const mpi::Communicator& ranks, Session& s);

}  // namespace ripple::apps
