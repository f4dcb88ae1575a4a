// The importer's own read of a glTF file's JSON, before tinygltf sees it: a nesting-depth scan that needs no
// parser, and a small document tree whose numbers keep their text, so "1.5" and "1.0" stay visible where
// tinygltf would quietly drop them. Internal to the importer (GltfFile.cpp, GltfJsonChecks.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ripple::apps::gltf {

// The deepest nesting of arrays and objects in `json` (1 for "[]"), brackets inside strings not counted.
// Linear and allocation-free, so it is safe on input no parser should see.
uint32_t jsonNestingDepth(std::string_view json);

// One JSON value. Strings and numbers point into the parsed text, which must outlive the tree.
struct JsonValue {
    enum class Kind : uint8_t { Null, Bool, Number, String, Array, Object };
    Kind kind = Kind::Null;
    bool boolean = false;
    std::string_view token;   // Number: its text as written; String: its raw contents, escapes not decoded
    std::vector<JsonValue> items;                           // Array
    std::vector<std::pair<std::string, JsonValue>> members; // Object, keys decoded, in file order

    // The member named `key`; the last one when a key repeats, as the parser tinygltf uses keeps the last.
    const JsonValue* find(std::string_view key) const;
    // Number whose text has no fraction or exponent: what tinygltf accepts as an integer.
    bool isIntegerToken() const;
    double number() const;
    std::string text() const;  // a String with its escapes decoded
    const char* kindName() const;  // "a string", "an array", ... for messages
};

// Parses `json` (RFC 8259; a UTF-8 byte order mark and trailing NUL padding are allowed, as tinygltf's parser
// allows them). Recursive: call it only on text whose jsonNestingDepth is bounded. On a syntax error returns
// nothing and sets `error` ("line 1, column 37: ...").
std::optional<JsonValue> parseJson(std::string_view json, std::string& error);

}  // namespace ripple::apps::gltf
