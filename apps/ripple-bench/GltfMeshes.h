// Reads the triangle geometry of a glTF 2.0 file (.glb or .gltf) into one core::TriangleMesh for ripple-bench.
#pragma once

#include "core/scene/SceneDescription.h"

#include <filesystem>

namespace ripple::bench {

// Flattens every TRIANGLES primitive reachable from the default scene (or from every root node where the
// file names no scene) into one indexed mesh, positions in world space. Accepts float VEC3 positions and
// uint8/16/32 indices. Throws std::runtime_error naming the file and the accessor on malformed data.
core::TriangleMesh loadGltfTriangles(const std::filesystem::path& file);

}  // namespace ripple::bench
