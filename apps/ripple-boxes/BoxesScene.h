// The "4x4x4 boxes" scene of the data-parallel ANARI paper, built through ANARI by one rank of several:
// 64 boxes dealt to the ranks by a fixed pseudo-random permutation, so most shadows cross rank boundaries.
#pragma once

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <cstdint>

namespace ripple::apps {

struct BoxesPart {
    ANARIWorld world = nullptr;  // committed; the caller releases it
    uint32_t boxes = 0;          // boxes this rank holds
    uint64_t triangles = 0;      // triangles this rank holds (boxes and floor)
};

// How the boxes are dealt to the ranks. Random: the paper's, box i to rank permutation[i] % ranks (the same
// on every rank count), the floor on the last rank: every rank's boxes are spread over the whole stack.
// Slabs: spatially, the 16 vertical columns of 4 boxes in x-major order cut into `ranks` runs, and the
// floor cut into the 16 cells under the columns, each with its column.
enum class BoxesPartition { Random, Slabs };

// This rank's boxes (see BoxesPartition), the lights (a point light and a warm sun) on rank 0 alone: the device
// gathers lights, so the other ranks need none. Each face of a box is cut into tessellation^2 quads (two
// triangles each), which changes the memory and trace cost but not the picture. Throws
// std::runtime_error when the device returns no object. lightsOnEveryRank: every rank adds the lights, as
// a device that renders each rank alone and composites (ripple_ptc) needs.
BoxesPart buildBoxesPart(ANARIDevice device, uint32_t rank, uint32_t ranks, uint32_t tessellation,
                         bool lightsOnEveryRank = false, BoxesPartition partition = BoxesPartition::Random);

// The view of the whole stack: the same on every rank, as data-parallel ANARI requires.
struct BoxesView {
    glm::vec3 position{9.0f, -11.0f, 9.0f};
    glm::vec3 target{0.0f, 0.0f, 2.5f};
    glm::vec3 up{0.0f, 0.0f, 1.0f};
    float fovy = 0.8f;
};

}  // namespace ripple::apps
