// The importer's own read of a glTF file's JSON, before tinygltf sees it: a nesting-depth scan that needs no
// parser, then nlohmann/json, whose numbers keep their kind (integer, unsigned or float), so "1.5" and "1.0"
// stay visible where tinygltf would quietly drop them. Internal to the importer (GltfFile.cpp,
// GltfJsonChecks.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ripple::apps::gltf {

// Objects keep their members in file order, so a check names the first bad member as the file lists it; a
// repeated key keeps its last value, as the parser tinygltf uses does.
using Json = nlohmann::ordered_json;

// The deepest nesting of arrays and objects in `json` (1 for "[]"), brackets inside strings not counted.
// Linear and allocation-free, so it is safe on input no parser should see.
uint32_t jsonNestingDepth(std::string_view json);

// Parses `json` (RFC 8259; a UTF-8 byte order mark and trailing NUL padding are allowed, as in tinygltf).
// Call it only on text whose jsonNestingDepth is bounded. On an error returns nothing and sets `error`
// ("parse error at line 1, column 37: ...").
std::optional<Json> parseJson(std::string_view json, std::string& error);

// The member named `key` of an object; null when absent or when `object` is not an object.
const Json* jsonMember(const Json& object, const char* key);
// "a string", "an array", ... for messages.
const char* jsonKindName(const Json& value);

}  // namespace ripple::apps::gltf
