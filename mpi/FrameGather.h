// The final image on rank 0: every rank resolved only the pixel bands it owns (core/render/PixelTiles.h);
// rank 0 receives each rank's bands and writes them into its own buffer. Other ranks' buffers are left as
// they were (ANARI leaves their mapped frames undefined).
#pragma once

#include "mpi/Communicator.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace ripple::mpi {

// `pixels` holds size.x * size.y pixels of bytesPerPixel bytes, row 0 at the bottom. Collective.
void gatherFrame(const Communicator& communicator, glm::uvec2 size, size_t bytesPerPixel, void* pixels);

}  // namespace ripple::mpi
