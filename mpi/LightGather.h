// Lights of every rank light the whole world: each rank contributes the lights of its part of the scene,
// and every rank gets all of them, in rank order, so applications need not replicate lights.
#pragma once

#include "core/scene/SceneDescription.h"
#include "mpi/Communicator.h"

#include <vector>

namespace ripple::mpi {

// Collective. With one rank, returns `local`.
std::vector<core::Light> gatherLights(const Communicator& communicator, const std::vector<core::Light>& local);

// Collective. Every other rank's light records (emissive triangles, world space), in rank order; this
// rank's own are left out, since its scene makes them itself.
std::vector<gpu::LightRecord> gatherForeignLightRecords(const Communicator& communicator,
                                                        const std::vector<gpu::LightRecord>& local);

}  // namespace ripple::mpi
