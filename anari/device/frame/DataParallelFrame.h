// Data-parallel ANARI at anariRenderFrame, which is collective: the ranks check that they render the same
// frame (creation order), world, size, camera and renderer settings, and a rank that cannot render says
// so to all; lights of every rank are gathered, the world's radius reduced, and an accumulation restart
// on any rank restarts it on all.
#pragma once

#include "core/render/PathTracer.h"
#include "mpi/Communicator.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace ripple::device {

// What every rank must agree on before rendering a frame together.
struct FrameIdentity {
    uint64_t frameIndex = 0;
    uint64_t worldIndex = 0;
    glm::uvec2 size{0, 0};
    uint32_t renderable = 0;
    uint32_t pixelSamples = 0;
    uint32_t maxPathLength = 0;
    uint32_t pad0 = 0;
    core::Camera camera;
};

// Collective. Empty when every rank agrees; otherwise one message, the same on every rank, naming the
// first rank that differs from rank 0 and how.
std::string ranksDisagree(const mpi::Communicator& ranks, const FrameIdentity& mine);

class SceneSync;

// Collective, on the rendering thread: the scene of `sync`, and when any rank rebuilt its scene, every
// rank's emissive-triangle lights shared with the others (rebuilding where they changed), so that each
// rank samples all emitters. `rebuilt` as SceneSync::scene sets it.
const core::Scene& sceneWithSharedEmitters(const mpi::Communicator& ranks, SceneSync& sync,
                                           const vk::Context& context, bool& rebuilt);

}  // namespace ripple::device
