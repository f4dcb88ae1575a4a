// The first stage of the glTF importer: the file read whole, its GLB container and raw JSON checked, and
// tinygltf's parse confined to approved files, with images decoded to RGBA8 from ranges this code has
// checked. Internal to GltfScene.cpp.
#pragma once

#include "io/gltf/GltfScene.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps::gltf {

// Parses `file` into `model`. Throws GltfError naming the file on a container, JSON or URI problem; images
// that cannot be decoded add a warning and stay empty.
void parseFile(const std::filesystem::path& file, const GltfLoadOptions& options, tinygltf::Model& model,
               std::vector<std::string>& warnings);

}  // namespace ripple::apps::gltf
