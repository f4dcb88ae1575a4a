// Committed world -> core::SceneDescription -> core::Scene, rebuilding only what changed since the last
// frame: an unchanged world subtree (by commit and unmap stamps) keeps its scene, and a rebuilt scene
// reuses the BLAS of every geometry whose (key, version) identity is unchanged.
#pragma once

#include "core/bvh/Aabb.h"
#include "core/scene/Scene.h"
#include "core/scene/SceneDescription.h"

#include <cstdint>
#include <memory>

namespace ripple::vk {
class Context;
}

namespace ripple::device {

class World;

class SceneSync {
public:
    SceneSync();
    ~SceneSync();

    // API thread. Brings the host description up to date with `world` (recommitting objects whose arrays
    // were rewritten since their commit) and says whether it changed since the previous call, which means
    // the accumulation starts over. Cheap when nothing changed: one walk over the committed objects.
    bool update(World& world);

    // Worker thread, with the GPU to itself. The core scene of the latest description, built when update()
    // found a change; `rebuilt` tells the caller to pass the scene's report on.
    const core::Scene& scene(const vk::Context& context, bool& rebuilt);
    // The traversal back-end the scene is built for (the device's "traversal"); a change rebuilds it.
    void setTraversal(core::Traversal traversal);
    // Data-parallel: this rank's own lights as of the latest update(), and the lights of all ranks that
    // replace them in the scene (mpi/LightGather), with the whole world's radius for picking lights by
    // power and its largest |coordinate| for ray offsets. Returns whether that changed the scene.
    const std::vector<core::Light>& localLights() const { return localLights_; }
    // Whether the latest description has a light (data-parallel: after setLights, any rank's) or a surface
    // that emits.
    bool lit() const;
    bool setLights(const std::vector<core::Light>& lights, float worldRadius, float worldMagnitude);
    // Data-parallel: the other ranks' emissive-triangle lights; returns whether they changed the scene.
    bool setForeignTriangleLights(std::vector<gpu::LightRecord> lights);
    // Scenes built so far: a camera-only change builds none.
    uint64_t builds() const { return builds_; }

private:
    const World* world_ = nullptr;
    uint64_t newestStamp_ = 0;
    bool pending_ = false;  // the description changed after the scene was built
    core::Traversal traversal_ = core::Traversal::Auto;
    core::SceneDescription description_;
    std::vector<core::Light> localLights_;
    std::unique_ptr<core::Scene> scene_;
    uint64_t builds_ = 0;
};

// The world-space bounds of everything renderable in the committed world (empty when nothing is).
// Host side only: no scene is built and nothing is uploaded.
bvh::Aabb worldBounds(World& world);

}  // namespace ripple::device
