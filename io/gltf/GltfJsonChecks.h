// Checks on a glTF file's raw JSON, before tinygltf parses it: tinygltf turns a non-integer index into
// "absent", a negative offset into 0 and a 2^32 index into 0, so these checks must see the JSON itself.
// Internal to the importer (GltfFile.cpp).
#pragma once

#include "io/gltf/GltfJson.h"

#include <string>

namespace ripple::apps::gltf {

// Throws GltfError "<name>: <JSON path>: <what>" ("scene.glb: nodes[3].mesh: 7 is out of range (the file
// has 2 meshes)") at the first problem: the document is not a glTF object with an 'asset', an index is not
// an integer or names nothing, an offset is negative or misaligned for its accessor, a stride is smaller
// than its element, an enum value is unknown, a camera or light parameter is outside glTF's range.
void checkGltfJson(const Json& root, const std::string& name);

}  // namespace ripple::apps::gltf
