// Reads the triangle geometry of a glTF 2.0 file (.glb or .gltf) into one core::TriangleMesh for ripple-bench.
#pragma once

#include "core/scene/SceneDescription.h"

#include <filesystem>

namespace ripple::bench {

// Flattens every instance of every TRIANGLES primitive of the default scene (or of every root node where the
// file names no scene) into one indexed mesh, positions in world space. Reads through the project's glTF
// importer (io/gltf/GltfScene.h) without decoding images; throws std::runtime_error (a GltfError) naming
// the file and the element on malformed data.
core::TriangleMesh loadGltfTriangles(const std::filesystem::path& file);

}  // namespace ripple::bench
