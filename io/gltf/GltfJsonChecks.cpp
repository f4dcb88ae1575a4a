// The glTF 2.0 schema's rules that the importer depends on, checked on the raw JSON so each error names the
// JSON path. Only present properties are checked where tinygltf or the converter has a default.
#include "io/gltf/GltfJsonChecks.h"

#include "io/gltf/GltfScene.h"

#include <algorithm>
#include <initializer_list>
#include <optional>

namespace ripple::apps::gltf {

namespace {

// A type test of nlohmann/json (&Json::is_object, ...).
using IsKind = bool (Json::*)() const noexcept;

std::string member(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }
std::string element(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

// Bytes per component of a glTF componentType; 0 for an unknown one.
int64_t componentBytes(int64_t type) {
    switch (type) {
        case 5120: case 5121: return 1;  // int8, uint8
        case 5122: case 5123: return 2;  // int16, uint16
        case 5125: case 5126: return 4;  // uint32, float32
        default: return 0;
    }
}

// Bytes of one element. Matrix columns start on 4-byte boundaries, as the specification lays them out.
int64_t elementBytes(const std::string& type, int64_t component) {
    if (type == "SCALAR") return component;
    if (type == "VEC2") return 2 * component;
    if (type == "VEC3") return 3 * component;
    if (type == "VEC4") return 4 * component;
    const int columns = type == "MAT2" ? 2 : type == "MAT3" ? 3 : 4;
    return columns * ((columns * component + 3) / 4 * 4);
}

class Checker {
public:
    Checker(const Json& root, const std::string& name) : root_(root), name_(name) {}

    void run() {
        if (!root_.is_object())
            throw GltfError(name_ + ": not a glTF file: the JSON is " + jsonKindName(root_) + ", not an object");
        const Json* asset = jsonMember(root_, "asset");
        if (!asset) throw GltfError(name_ + ": not a glTF file: no 'asset' object");
        if (!asset->is_object())
            throw GltfError(name_ + ": not a glTF file: 'asset' is " + jsonKindName(*asset) + ", not an object");

        for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images",
                                "materials", "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
            objects(root_, key, "");
        strings(root_, "extensionsUsed", "");
        strings(root_, "extensionsRequired", "");
        const std::string lightsPath = "extensions.KHR_lights_punctual.lights";
        if (const Json* ext = object(root_, "extensions", ""))
            if (const Json* khr = object(*ext, "KHR_lights_punctual", "extensions"))
                lights_ = objects(*khr, "lights", "extensions.KHR_lights_punctual");

        index(root_, "scene", "", "scenes");
        each("scenes", [&](const Json& scene, const std::string& path) { indices(scene, "nodes", path, "nodes"); });
        each("nodes", [&](const Json& node, const std::string& path) { this->node(node, path); });
        each("meshes", [&](const Json& mesh, const std::string& path) { this->mesh(mesh, path); });
        each("bufferViews", [&](const Json& view, const std::string& path) { bufferView(view, path); });
        each("accessors", [&](const Json& accessor, const std::string& path) { this->accessor(accessor, path); });
        each("buffers", [&](const Json& buffer, const std::string& path) {
            integer(buffer, "byteLength", path, 1, true);
            string(buffer, "uri", path);
        });
        each("images", [&](const Json& image, const std::string& path) {
            string(image, "uri", path);
            string(image, "mimeType", path);
            index(image, "bufferView", path, "bufferViews");
        });
        each("samplers", [&](const Json& sampler, const std::string& path) {
            oneOf(sampler, "magFilter", path, {9728, 9729});
            oneOf(sampler, "minFilter", path, {9728, 9729, 9984, 9985, 9986, 9987});
            oneOf(sampler, "wrapS", path, {33071, 33648, 10497});
            oneOf(sampler, "wrapT", path, {33071, 33648, 10497});
        });
        each("textures", [&](const Json& texture, const std::string& path) {
            index(texture, "source", path, "images");
            index(texture, "sampler", path, "samplers");
        });
        each("materials", [&](const Json& material, const std::string& path) { this->material(material, path); });
        each("cameras", [&](const Json& camera, const std::string& path) { this->camera(camera, path); });
        if (lights_)
            for (size_t i = 0; i < lights_->size(); ++i) light((*lights_)[i], element(lightsPath, i));
        each("skins", [&](const Json& skin, const std::string& path) {
            indices(skin, "joints", path, "nodes");
            index(skin, "skeleton", path, "nodes");
            index(skin, "inverseBindMatrices", path, "accessors");
        });
        each("animations", [&](const Json& animation, const std::string& path) { this->animation(animation, path); });
    }

private:
    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw GltfError(name_ + ": " + path + ": " + what);
    }

    template <typename F>
    void each(const char* collection, F&& check) const {
        if (const Json* items = jsonMember(root_, collection))
            for (size_t i = 0; i < items->size(); ++i) check((*items)[i], element(collection, i));
    }

    size_t count(const char* collection) const {
        if (std::string_view(collection) == "lights") return lights_ ? lights_->size() : 0;
        const Json* items = jsonMember(root_, collection);
        return items ? items->size() : 0;
    }

    const Json* typed(const Json& parent, const char* key, const std::string& path, IsKind is,
                      const char* expected) const {
        const Json* v = jsonMember(parent, key);
        if (v && !(v->*is)()) fail(member(path, key), std::string("expected ") + expected + ", found " + jsonKindName(*v));
        return v;
    }
    const Json* object(const Json& parent, const char* key, const std::string& path) const {
        return typed(parent, key, path, &Json::is_object, "an object");
    }
    const Json* array(const Json& parent, const char* key, const std::string& path) const {
        return typed(parent, key, path, &Json::is_array, "an array");
    }
    const Json* string(const Json& parent, const char* key, const std::string& path) const {
        return typed(parent, key, path, &Json::is_string, "a string");
    }

    // An array whose elements are all objects.
    const Json* objects(const Json& parent, const char* key, const std::string& path) const {
        const Json* items = array(parent, key, path);
        if (items)
            for (size_t i = 0; i < items->size(); ++i)
                if (!(*items)[i].is_object())
                    fail(element(member(path, key), i), std::string("expected an object, found ") + jsonKindName((*items)[i]));
        return items;
    }
    void strings(const Json& parent, const char* key, const std::string& path) const {
        if (const Json* items = array(parent, key, path))
            for (size_t i = 0; i < items->size(); ++i)
                if (!(*items)[i].is_string())
                    fail(element(member(path, key), i), std::string("expected a string, found ") + jsonKindName((*items)[i]));
    }

    // The value at `path` as an integer. A number written with a fraction or an exponent (1.0, 1e2) is a float
    // to nlohmann/json, as to tinygltf, which reads only integers as integers.
    int64_t integerValue(const Json& v, const std::string& path) const {
        if (!v.is_number()) fail(path, std::string("expected an integer, found ") + jsonKindName(v));
        if (v.is_number_float()) fail(path, "expected an integer, found " + v.dump());
        if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)) fail(path, v.dump() + " is out of range");
        return v.get<int64_t>();
    }

    std::optional<int64_t> integer(const Json& parent, const char* key, const std::string& path, int64_t min,
                                   bool required = false) const {
        const Json* v = jsonMember(parent, key);
        if (!v) {
            if (required) fail(path, std::string("'") + key + "' is missing");
            return std::nullopt;
        }
        const int64_t value = integerValue(*v, member(path, key));
        if (value < min)
            fail(member(path, key), std::to_string(value) + (min == 0 ? " is negative" : " is less than " + std::to_string(min)));
        return value;
    }

    void oneOf(const Json& parent, const char* key, const std::string& path, std::initializer_list<int64_t> allowed) const {
        const std::optional<int64_t> v = integer(parent, key, path, INT64_MIN);
        if (v && std::find(allowed.begin(), allowed.end(), *v) == allowed.end())
            fail(member(path, key), std::to_string(*v) + " is not a value glTF defines here");
    }

    void checkIndex(const Json& v, const std::string& path, const char* collection) const {
        const int64_t value = integerValue(v, path);
        const size_t n = count(collection);
        if (value < 0 || uint64_t(value) >= n)
            fail(path, std::to_string(value) + " is out of range (the file has " + std::to_string(n) + " " + collection + ")");
    }
    std::optional<int64_t> index(const Json& parent, const char* key, const std::string& path,
                                 const char* collection, bool required = false) const {
        const Json* v = jsonMember(parent, key);
        if (!v) {
            if (required) fail(path, std::string("'") + key + "' is missing");
            return std::nullopt;
        }
        checkIndex(*v, member(path, key), collection);
        return integerValue(*v, member(path, key));
    }
    void indices(const Json& parent, const char* key, const std::string& path, const char* collection) const {
        if (const Json* items = array(parent, key, path))
            for (size_t i = 0; i < items->size(); ++i) checkIndex((*items)[i], element(member(path, key), i), collection);
    }
    // An object whose every member is an index ("attributes": {"POSITION": 0, ...}).
    void indexMap(const Json& parent, const char* key, const std::string& path, const char* collection) const {
        if (const Json* map = object(parent, key, path))
            for (const auto& entry : map->items()) checkIndex(entry.value(), member(path, key) + "." + entry.key(), collection);
    }

    const Json* number(const Json& parent, const char* key, const std::string& path) const {
        return typed(parent, key, path, &Json::is_number, "a number");
    }
    // A number that glTF bounds below: exclusive (> min) or inclusive (>= min).
    std::optional<double> bounded(const Json& parent, const char* key, const std::string& path, double min,
                                  bool exclusive) const {
        const Json* v = number(parent, key, path);
        if (!v) return std::nullopt;
        const double value = v->get<double>();
        if (exclusive ? !(value > min) : !(value >= min))
            fail(member(path, key), std::string("must be ") + (exclusive ? "greater than " : "at least ") +
                                        std::to_string(int(min)) + ", found " + v->dump());
        return value;
    }

    void node(const Json& n, const std::string& path) const {
        index(n, "camera", path, "cameras");
        index(n, "mesh", path, "meshes");
        index(n, "skin", path, "skins");
        indices(n, "children", path, "nodes");
        if (const Json* ext = object(n, "extensions", path))
            if (const Json* khr = object(*ext, "KHR_lights_punctual", member(path, "extensions")))
                index(*khr, "light", member(path, "extensions.KHR_lights_punctual"), "lights", true);
    }

    void mesh(const Json& m, const std::string& path) const {
        const Json* primitives = objects(m, "primitives", path);
        if (!primitives) return;
        for (size_t i = 0; i < primitives->size(); ++i) {
            const Json& p = (*primitives)[i];
            const std::string at = element(member(path, "primitives"), i);
            indexMap(p, "attributes", at, "accessors");
            index(p, "indices", at, "accessors");
            index(p, "material", at, "materials");
            oneOf(p, "mode", at, {0, 1, 2, 3, 4, 5, 6});
            if (const Json* targets = objects(p, "targets", at))
                for (size_t t = 0; t < targets->size(); ++t)
                    for (const auto& entry : (*targets)[t].items())
                        checkIndex(entry.value(), element(member(at, "targets"), t) + "." + entry.key(), "accessors");
        }
    }

    void bufferView(const Json& v, const std::string& path) const {
        index(v, "buffer", path, "buffers", true);
        integer(v, "byteOffset", path, 0);
        integer(v, "byteLength", path, 1, true);
        if (const std::optional<int64_t> stride = integer(v, "byteStride", path, 0); stride && (*stride < 4 || *stride > 252 || *stride % 4))
            fail(member(path, "byteStride"), std::to_string(*stride) + " is not a multiple of 4 from 4 to 252");
    }

    // A view's byteOffset and byteStride; the view itself was checked already.
    std::pair<int64_t, int64_t> viewLayout(int64_t view) const {
        const Json& v = (*jsonMember(root_, "bufferViews"))[size_t(view)];
        return {integer(v, "byteOffset", "", 0).value_or(0), integer(v, "byteStride", "", 0).value_or(0)};
    }

    // accessor.byteOffset + bufferView.byteOffset must be a multiple of the component size.
    void aligned(const std::string& path, int64_t view, int64_t offset, int64_t component) const {
        const int64_t viewOffset = viewLayout(view).first;
        if ((offset + viewOffset) % component)
            fail(member(path, "byteOffset"), std::to_string(offset) + " plus bufferViews[" + std::to_string(view) +
                                                 "].byteOffset " + std::to_string(viewOffset) + " is " +
                                                 std::to_string(offset + viewOffset) +
                                                 ", not a multiple of the component size " + std::to_string(component));
    }

    void accessor(const Json& a, const std::string& path) const {
        const std::optional<int64_t> view = index(a, "bufferView", path, "bufferViews");
        const int64_t offset = integer(a, "byteOffset", path, 0).value_or(0);
        const int64_t componentType = *integer(a, "componentType", path, INT64_MIN, true);
        const int64_t component = componentBytes(componentType);
        if (!component) fail(member(path, "componentType"), std::to_string(componentType) + " is not a glTF component type");
        integer(a, "count", path, 1, true);
        const Json* type = string(a, "type", path);
        if (!type) fail(path, "'type' is missing");
        const std::string& typeName = type->get_ref<const std::string&>();
        static const char* const types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
        if (std::find(std::begin(types), std::end(types), typeName) == std::end(types))
            fail(member(path, "type"), "'" + typeName + "' is not a glTF accessor type");
        typed(a, "normalized", path, &Json::is_boolean, "a boolean");
        if (view) {
            aligned(path, *view, offset, component);
            const int64_t stride = viewLayout(*view).second;
            const int64_t bytes = elementBytes(typeName, component);
            const std::string named = path + " (bufferView " + std::to_string(*view) + ")";
            if (stride && stride < bytes)
                fail(named, "byteStride " + std::to_string(stride) + " is smaller than the element size " + std::to_string(bytes));
            if (stride % component)
                fail(named, "byteStride " + std::to_string(stride) + " is not a multiple of the component size " +
                                std::to_string(component));
        }
        const Json* sparse = object(a, "sparse", path);
        if (!sparse) return;
        const std::string at = member(path, "sparse");
        integer(*sparse, "count", at, 1, true);
        const Json* sparseIndices = object(*sparse, "indices", at);
        const Json* sparseValues = object(*sparse, "values", at);
        if (!sparseIndices) fail(at, "'indices' is missing");
        if (!sparseValues) fail(at, "'values' is missing");
        const std::string indicesPath = member(at, "indices"), valuesPath = member(at, "values");
        const int64_t indicesView = *index(*sparseIndices, "bufferView", indicesPath, "bufferViews", true);
        const int64_t indexType = *integer(*sparseIndices, "componentType", indicesPath, INT64_MIN, true);
        if (indexType != 5121 && indexType != 5123 && indexType != 5125)
            fail(member(indicesPath, "componentType"), std::to_string(indexType) + " is not uint8, uint16 or uint32");
        aligned(indicesPath, indicesView,
                integer(*sparseIndices, "byteOffset", indicesPath, 0).value_or(0), componentBytes(indexType));
        const int64_t valuesView = *index(*sparseValues, "bufferView", valuesPath, "bufferViews", true);
        aligned(valuesPath, valuesView, integer(*sparseValues, "byteOffset", valuesPath, 0).value_or(0),
                component);
    }

    void textureInfo(const Json& parent, const char* key, const std::string& path) const {
        const Json* info = object(parent, key, path);
        if (!info) return;
        index(*info, "index", member(path, key), "textures", true);
        integer(*info, "texCoord", member(path, key), 0);
    }

    void material(const Json& m, const std::string& path) const {
        if (const Json* pbr = object(m, "pbrMetallicRoughness", path)) {
            textureInfo(*pbr, "baseColorTexture", member(path, "pbrMetallicRoughness"));
            textureInfo(*pbr, "metallicRoughnessTexture", member(path, "pbrMetallicRoughness"));
        }
        textureInfo(m, "normalTexture", path);
        textureInfo(m, "occlusionTexture", path);
        textureInfo(m, "emissiveTexture", path);
        bounded(m, "alphaCutoff", path, 0.0, false);
    }

    void camera(const Json& c, const std::string& path) const {
        const Json* type = string(c, "type", path);
        if (!type) fail(path, "'type' is missing");
        const std::string& kind = type->get_ref<const std::string&>();
        if (kind != "perspective" && kind != "orthographic")
            fail(member(path, "type"), "'" + kind + "' is neither perspective nor orthographic");
        const Json* p = object(c, kind.c_str(), path);
        if (!p) fail(path, "'" + kind + "' is missing");
        const std::string at = member(path, kind.c_str());
        std::optional<double> znear;
        if (kind == "perspective") {
            bounded(*p, "aspectRatio", at, 0.0, true);
            bounded(*p, "yfov", at, 0.0, true);
            znear = bounded(*p, "znear", at, 0.0, true);
        } else {
            number(*p, "xmag", at);
            number(*p, "ymag", at);
            znear = bounded(*p, "znear", at, 0.0, false);
        }
        const std::optional<double> zfar = bounded(*p, "zfar", at, 0.0, true);
        if (znear && zfar && !(*zfar > *znear))
            fail(member(at, "zfar"), "must be greater than znear (" + jsonMember(*p, "znear")->dump() + "), found " +
                                         jsonMember(*p, "zfar")->dump());
    }

    void light(const Json& l, const std::string& path) const {
        const Json* type = string(l, "type", path);
        if (!type) fail(path, "'type' is missing");
        const std::string& kind = type->get_ref<const std::string&>();
        if (kind != "directional" && kind != "point" && kind != "spot")
            fail(member(path, "type"), "'" + kind + "' is not directional, point or spot");
        bounded(l, "intensity", path, 0.0, false);
        bounded(l, "range", path, 0.0, true);
        if (const Json* spot = object(l, "spot", path)) {
            number(*spot, "innerConeAngle", member(path, "spot"));
            number(*spot, "outerConeAngle", member(path, "spot"));
        }
    }

    void animation(const Json& a, const std::string& path) const {
        const Json* samplers = objects(a, "samplers", path);
        const size_t samplerCount = samplers ? samplers->size() : 0;
        for (size_t i = 0; i < samplerCount; ++i) {
            index((*samplers)[i], "input", element(member(path, "samplers"), i), "accessors", true);
            index((*samplers)[i], "output", element(member(path, "samplers"), i), "accessors", true);
        }
        if (const Json* channels = objects(a, "channels", path))
            for (size_t i = 0; i < channels->size(); ++i) {
                const std::string at = element(member(path, "channels"), i);
                const Json& channel = (*channels)[i];
                if (const Json* s = jsonMember(channel, "sampler")) {
                    const int64_t value = integerValue(*s, member(at, "sampler"));
                    if (value < 0 || uint64_t(value) >= samplerCount)
                        fail(member(at, "sampler"), std::to_string(value) + " is out of range (the animation has " +
                                                        std::to_string(samplerCount) + " samplers)");
                }
                if (const Json* target = object(channel, "target", at)) index(*target, "node", member(at, "target"), "nodes");
            }
    }

    const Json& root_;
    const std::string& name_;
    const Json* lights_ = nullptr;
};

}  // namespace

void checkGltfJson(const Json& root, const std::string& name) { Checker(root, name).run(); }

}  // namespace ripple::apps::gltf
