// One rank's share of a glTF scene for data-parallel rendering, so that no rank holds the whole scene:
// round robin over mesh instances, or a k-d split of the scene's triangles into one region per rank.
#pragma once

#include "io/gltf/GltfScene.h"

#include <cstdint>
#include <string>

namespace ripple::apps {

enum class PartitionKind {
    RoundRobin,  // instance i goes to rank i % ranks, whole (meshes keep their sharing)
    Spatial,     // triangles split by a k-d tree over their world-space centroids, balanced by count
};

// "round-robin" or "spatial"; throws std::invalid_argument naming the accepted values otherwise.
PartitionKind parsePartitionKind(const std::string& name);

// The part of `whole` that `rank` of `ranks` holds: its instances (round robin) or its triangles (spatial,
// each instance's share a geometry of its own with only the vertices it uses); geometries and meshes no
// instance of this rank uses are dropped. Lights, cameras, materials, textures and the whole scene's bounds
// stay on every rank, so every rank frames the same view and picks the same lighting; only one rank should
// turn the lights into ANARI lights (data-parallel ANARI gathers them). One rank gets `whole` unchanged.
GltfScene partitionScene(const GltfScene& whole, uint32_t rank, uint32_t ranks, PartitionKind kind);

}  // namespace ripple::apps
