// JSON for the importer's own checks: the depth scan, and nlohmann/json's parser in the importer's terms.
#include "io/gltf/GltfJson.h"

#include <algorithm>

namespace ripple::apps::gltf {

uint32_t jsonNestingDepth(std::string_view json) {
    uint32_t depth = 0, deepest = 0;
    bool inString = false;
    for (size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (inString) {
            if (c == '\\') ++i;  // the escaped character cannot end the string
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

std::optional<Json> parseJson(std::string_view json, std::string& error) {
    try {
        return Json::parse(json.begin(), json.end());
    } catch (const Json::exception& e) {  // parse_error, or out_of_range for a number beyond double
        // nlohmann's message without its "[json.exception.parse_error.101] " prefix.
        const std::string_view what = e.what();
        const size_t close = what.find("] ");
        error = what.substr(what.starts_with("[json.exception.") && close != std::string_view::npos ? close + 2 : 0);
        return std::nullopt;
    }
}

const Json* jsonMember(const Json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

const char* jsonKindName(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null: return "null";
        case Json::value_t::boolean: return "a boolean";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float: return "a number";
        case Json::value_t::string: return "a string";
        case Json::value_t::array: return "an array";
        case Json::value_t::object: return "an object";
        default: return "a value";
    }
}

}  // namespace ripple::apps::gltf
