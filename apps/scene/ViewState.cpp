// Reading and writing view-state files (see ViewState.h).
#include "apps/scene/ViewState.h"

#include "io/FileRead.h"
#include "io/FileWrite.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ripple::apps {
namespace {

using Json = nlohmann::json;

constexpr int kVersion = 1;

class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(file_ + ": " + what); }

    const Json& member(const Json& object, const char* name, const std::string& where) const {
        const auto it = object.find(name);
        if (it == object.end()) fail("missing \"" + std::string(name) + "\"" + where);
        return *it;
    }

    float number(const Json& value, const std::string& name) const {
        if (!value.is_number()) fail("\"" + name + "\" must be a number");
        const double v = value.get<double>();
        if (!std::isfinite(v) || std::abs(v) > 3.0e38) fail("\"" + name + "\" must be finite");
        return float(v);
    }

    template <int N>
    glm::vec<N, float> vector(const Json& value, const std::string& name) const {
        if (!value.is_array() || value.size() != N) fail("\"" + name + "\" must be an array of " + std::to_string(N) + " numbers");
        glm::vec<N, float> v;
        for (int i = 0; i < N; ++i) v[i] = number(value[size_t(i)], name + "[" + std::to_string(i) + "]");
        return v;
    }

    // Member `key` of the list entry called `name` ("lights[0]").
    const Json& entry(const Json& record, const char* key, const std::string& name) const {
        return member(record, key, " in \"" + name + "\"");
    }

    std::string label(const Json& record, const std::string& name) const {
        const Json& value = entry(record, "label", name);
        if (!value.is_string()) fail("\"" + name + ".label\" must be a string");
        return value.get<std::string>();
    }

    // An array member of at most `limit` entries, or a failure naming it.
    const Json& list(const Json& value, const std::string& name, size_t limit) const {
        if (!value.is_array() || value.empty() || value.size() > limit)
            fail("\"" + name + "\" must be an array of 1 to " + std::to_string(limit) + " entries");
        return value;
    }

    int32_t integer(const Json& value, const std::string& name, int64_t lowest, int64_t highest) const {
        if (!value.is_number_integer()) fail("\"" + name + "\" must be an integer");
        const int64_t v = value.get<int64_t>();
        if (v < lowest || v > highest)
            fail("\"" + name + "\" is " + std::to_string(v) + ", not within " + std::to_string(lowest) + ".." + std::to_string(highest));
        return int32_t(v);
    }

private:
    std::string file_;
};

constexpr size_t kMaxRecords = 4096, kMaxTableEntries = 65536;

// "lights", "volumes", "isosurfaces" (see ViewState.h).
void readSceneEdits(const Reader& r, const Json& root, ViewState& state) {
    if (const auto it = root.find("lights"); it != root.end()) {
        state.lights.emplace();
        for (const Json& record : r.list(*it, "lights", kMaxRecords)) {
            const std::string name = "lights[" + std::to_string(state.lights->size()) + "]";
            if (!record.is_object()) r.fail("\"" + name + "\" must be an object");
            EditableLight light;
            light.label = r.label(record, name);
            light.color = r.vector<3>(r.entry(record, "color", name), name + ".color");
            light.intensity = r.number(r.entry(record, "intensity", name), name + ".intensity");
            if (light.color.r < 0.0f || light.color.g < 0.0f || light.color.b < 0.0f || light.intensity < 0.0f)
                r.fail("\"" + name + "\" must not have a negative colour or intensity");
            if (const auto v = record.find("direction"); v != record.end()) {
                light.direction = r.vector<3>(*v, name + ".direction");
                const float lengthSquared = glm::dot(*light.direction, *light.direction);
                if (!(lengthSquared > 0.0f) || !std::isfinite(lengthSquared))
                    r.fail("\"" + name + ".direction\" must not be zero or overflow");
            }
            light.rotationDegrees = std::nanf("");
            if (const auto v = record.find("rotation"); v != record.end()) light.rotationDegrees = r.number(*v, name + ".rotation");
            state.lights->push_back(std::move(light));
        }
    }
    if (const auto it = root.find("volumes"); it != root.end()) {
        state.volumes.emplace();
        for (const Json& record : r.list(*it, "volumes", kMaxRecords)) {
            const std::string name = "volumes[" + std::to_string(state.volumes->size()) + "]";
            if (!record.is_object()) r.fail("\"" + name + "\" must be an object");
            EditableVolume volume;
            volume.label = r.label(record, name);
            if (const auto v = record.find("colorMap"); v != record.end()) {
                if (!v->is_string()) r.fail("\"" + name + ".colorMap\" must be a string");
                volume.colorMap = v->get<std::string>();
            }
            const Json& colors = r.list(r.entry(record, "colors", name), name + ".colors", kMaxTableEntries);
            for (const Json& c : colors) {
                volume.colors.push_back(r.vector<3>(c, name + ".colors[" + std::to_string(volume.colors.size()) + "]"));
                const glm::vec3& rgb = volume.colors.back();
                if (rgb.r < 0.0f || rgb.g < 0.0f || rgb.b < 0.0f) r.fail("\"" + name + ".colors\" must not be negative");
            }
            const Json& opacities = r.list(r.entry(record, "opacities", name), name + ".opacities", kMaxTableEntries);
            for (const Json& o : opacities) {
                volume.opacities.push_back(r.number(o, name + ".opacities[" + std::to_string(volume.opacities.size()) + "]"));
                if (volume.opacities.back() < 0.0f || volume.opacities.back() > 1.0f)
                    r.fail("\"" + name + ".opacities\" must lie within 0..1");
            }
            volume.valueRange = r.vector<2>(r.entry(record, "valueRange", name), name + ".valueRange");
            if (!(volume.valueRange.x <= volume.valueRange.y)) r.fail("\"" + name + ".valueRange\" must not be inverted");
            volume.unitDistance = r.number(r.entry(record, "unitDistance", name), name + ".unitDistance");
            if (!(volume.unitDistance > 0.0f)) r.fail("\"" + name + ".unitDistance\" must be positive");
            state.volumes->push_back(std::move(volume));
        }
    }
    if (const auto it = root.find("isosurfaces"); it != root.end()) {
        state.isosurfaces.emplace();
        for (const Json& record : r.list(*it, "isosurfaces", kMaxRecords)) {
            const std::string name = "isosurfaces[" + std::to_string(state.isosurfaces->size()) + "]";
            if (!record.is_object()) r.fail("\"" + name + "\" must be an object");
            EditableIsosurface isosurface;
            isosurface.label = r.label(record, name);
            isosurface.isovalue = r.number(r.entry(record, "isovalue", name), name + ".isovalue");
            state.isosurfaces->push_back(std::move(isosurface));
        }
    }
}

// The records of one kind in the file against the scene's: the same count, the same labels in order.
template <typename Record>
void checkRecords(const Reader& r, const std::vector<Record>& inFile, const std::vector<Record>& inScene, const char* kind) {
    if (inFile.size() != inScene.size())
        r.fail(std::string("the view file lists ") + std::to_string(inFile.size()) + " " + kind + "(s), the scene has " +
               std::to_string(inScene.size()) + " (give both programs the same scene)");
    for (size_t i = 0; i < inFile.size(); ++i)
        if (inFile[i].label != inScene[i].label)
            r.fail(std::string(kind) + " " + std::to_string(i) + " is \"" + inFile[i].label + "\" in the view file but \"" +
                   inScene[i].label + "\" in the scene");
}

}  // namespace

ViewState readViewState(const std::filesystem::path& file) {
    const Reader r(file.string());
    std::string text, error;
    if (!readRegularFile(file, kMaxViewFileBytes, false, text, error)) r.fail("cannot open the view file (" + error + ")");
    Json root;
    try {
        root = Json::parse(text);
    } catch (const Json::exception& e) {  // malformed, or a number past a double (1e999)
        r.fail(std::string("not JSON: ") + e.what());
    }
    if (!root.is_object()) r.fail("not a view-state object");
    const int32_t version = r.integer(r.member(root, "ripple-view-state", ""), "ripple-view-state", 1, 1 << 30);
    if (version != kVersion) r.fail("view-state version " + std::to_string(version) + " is not one this program reads (" + std::to_string(kVersion) + ")");

    ViewState state;
    const Json& camera = r.member(root, "camera", "");
    if (!camera.is_object()) r.fail("\"camera\" must be an object");
    const Json& type = r.member(camera, "type", " in \"camera\"");
    if (type != "perspective" && type != "orthographic") r.fail("\"camera.type\" must be \"perspective\" or \"orthographic\"");
    CameraView& view = state.camera;
    view.orthographic = type == "orthographic";
    view.position = r.vector<3>(r.member(camera, "position", " in \"camera\""), "camera.position");
    view.direction = r.vector<3>(r.member(camera, "direction", " in \"camera\""), "camera.direction");
    view.up = r.vector<3>(r.member(camera, "up", " in \"camera\""), "camera.up");
    const float lengthSquared = glm::dot(view.direction, view.direction);
    if (!(lengthSquared > 0.0f) || !std::isfinite(lengthSquared)) r.fail("\"camera.direction\" must not be zero or overflow");
    const float crossSquared = glm::dot(glm::cross(view.direction, view.up), glm::cross(view.direction, view.up));
    if (!(crossSquared > 0.0f) || !std::isfinite(glm::dot(view.up, view.up)))
        r.fail("\"camera.up\" must not be zero, overflow or lie along the direction");
    if (view.orthographic) {
        view.height = r.number(r.member(camera, "height", " in an orthographic \"camera\""), "camera.height");
        if (!(view.height > 0.0f)) r.fail("\"camera.height\" must be positive");
    } else {
        view.fovy = r.number(r.member(camera, "fovy", " in a perspective \"camera\""), "camera.fovy");
        if (!(view.fovy > 0.0f && view.fovy < 3.14159265f)) r.fail("\"camera.fovy\" must be within (0, pi) radians");
        if (const auto v = camera.find("apertureRadius"); v != camera.end()) {
            view.apertureRadius = r.number(*v, "camera.apertureRadius");
            if (!(view.apertureRadius >= 0.0f)) r.fail("\"camera.apertureRadius\" must not be negative");
        }
        if (const auto v = camera.find("focusDistance"); v != camera.end()) {
            view.focusDistance = r.number(*v, "camera.focusDistance");
            if (!(view.focusDistance > 0.0f)) r.fail("\"camera.focusDistance\" must be positive");
        }
    }

    if (const auto it = root.find("renderer"); it != root.end()) {
        const Json& renderer = *it;
        if (!renderer.is_object()) r.fail("\"renderer\" must be an object");
        if (const auto s = renderer.find("subtype"); s != renderer.end()) {
            if (!s->is_string() || s->get<std::string>().empty()) r.fail("\"renderer.subtype\" must be a non-empty string");
            state.renderer = s->get<std::string>();
        }
        if (const auto v = renderer.find("pixelSamples"); v != renderer.end())
            state.pixelSamples = r.integer(*v, "renderer.pixelSamples", 1, 1024);
        if (const auto v = renderer.find("maxPathLength"); v != renderer.end())
            state.maxPathLength = r.integer(*v, "renderer.maxPathLength", 1, 1024);
        if (const auto v = renderer.find("ambientRadiance"); v != renderer.end()) {
            state.ambientRadiance = r.number(*v, "renderer.ambientRadiance");
            if (*state.ambientRadiance < 0.0f) r.fail("\"renderer.ambientRadiance\" must not be negative");
        }
        if (const auto v = renderer.find("background"); v != renderer.end())
            state.background = r.vector<4>(*v, "renderer.background");
        if (const auto t = renderer.find("traversal"); t != renderer.end()) {
            if (!t->is_string() || (*t != "auto" && *t != "software" && *t != "rayQuery"))
                r.fail("\"renderer.traversal\" must be \"auto\", \"software\" or \"rayQuery\"");
            state.traversal = t->get<std::string>();
        }
    }
    if (const auto it = root.find("size"); it != root.end()) {
        if (!it->is_array() || it->size() != 2) r.fail("\"size\" must be [width, height]");
        state.size = glm::uvec2(uint32_t(r.integer((*it)[0], "size[0]", 1, 16384)), uint32_t(r.integer((*it)[1], "size[1]", 1, 16384)));
    }
    readSceneEdits(r, root, state);
    return state;
}

void writeViewState(const std::filesystem::path& file, const ViewState& state) {
    const CameraView& v = state.camera;
    auto array = [](auto vector) {
        Json a = Json::array();
        for (int i = 0; i < vector.length(); ++i) a.push_back(vector[i]);
        return a;
    };
    Json camera = {{"type", v.orthographic ? "orthographic" : "perspective"},
                   {"position", array(v.position)},
                   {"direction", array(v.direction)},
                   {"up", array(v.up)}};
    if (v.orthographic) camera["height"] = v.height;
    else camera["fovy"] = v.fovy;
    if (!v.orthographic && v.apertureRadius > 0.0f) {
        camera["apertureRadius"] = v.apertureRadius;
        camera["focusDistance"] = v.focusDistance;
    }
    Json renderer = Json::object();
    if (state.renderer) renderer["subtype"] = *state.renderer;
    if (state.pixelSamples) renderer["pixelSamples"] = *state.pixelSamples;
    if (state.maxPathLength) renderer["maxPathLength"] = *state.maxPathLength;
    if (state.ambientRadiance) renderer["ambientRadiance"] = *state.ambientRadiance;
    if (state.background) renderer["background"] = array(*state.background);
    if (state.traversal) renderer["traversal"] = *state.traversal;
    Json root = {{"ripple-view-state", kVersion}, {"camera", camera}, {"renderer", renderer}};
    if (state.size) root["size"] = {state.size->x, state.size->y};
    if (state.lights && !state.lights->empty()) {
        Json& lights = root["lights"] = Json::array();
        for (const EditableLight& l : *state.lights) {
            Json record = {{"label", l.label}, {"color", array(l.color)}, {"intensity", l.intensity}};
            if (l.direction) record["direction"] = array(*l.direction);
            if (l.subtype == "hdri") record["rotation"] = l.rotationDegrees;
            lights.push_back(std::move(record));
        }
    }
    if (state.volumes && !state.volumes->empty()) {
        Json& volumes = root["volumes"] = Json::array();
        for (const EditableVolume& volume : *state.volumes) {
            Json colors = Json::array();
            for (const glm::vec3& c : volume.colors) colors.push_back(array(c));
            Json record = {{"label", volume.label}, {"colors", colors}, {"opacities", volume.opacities},
                           {"valueRange", array(volume.valueRange)}, {"unitDistance", volume.unitDistance}};
            if (!volume.colorMap.empty()) record["colorMap"] = volume.colorMap;
            volumes.push_back(std::move(record));
        }
    }
    if (state.isosurfaces && !state.isosurfaces->empty()) {
        Json& isosurfaces = root["isosurfaces"] = Json::array();
        for (const EditableIsosurface& i : *state.isosurfaces)
            isosurfaces.push_back({{"label", i.label}, {"isovalue", i.isovalue}});
    }
    writeFileAtomically(file, root.dump(2) + "\n", "the view file");
}

SceneEditRequests applyViewEdits(const ViewState& state, SceneEdits& edits, bool withLights,
                                 const std::filesystem::path& file) {
    const Reader r(file.string());
    SceneEditRequests changed;
    if (state.lights && withLights) {
        checkRecords(r, *state.lights, edits.lights, "light");
        for (size_t i = 0; i < edits.lights.size(); ++i) {
            const EditableLight& saved = (*state.lights)[i];
            EditableLight& light = edits.lights[i];
            light.color = saved.color;
            light.intensity = saved.intensity;
            if (light.direction && saved.direction) light.direction = saved.direction;
            if (!std::isnan(saved.rotationDegrees)) light.rotationDegrees = saved.rotationDegrees;
            changed.lights.insert(i);
        }
    }
    if (state.volumes) {
        checkRecords(r, *state.volumes, edits.volumes, "volume");
        for (size_t i = 0; i < edits.volumes.size(); ++i) {
            const EditableVolume& saved = (*state.volumes)[i];
            EditableVolume& volume = edits.volumes[i];
            volume.colors = saved.colors;
            volume.opacities = saved.opacities;
            volume.valueRange = saved.valueRange;
            volume.unitDistance = saved.unitDistance;
            volume.colorMap = saved.colorMap;
            changed.volumes.insert(i);
        }
    }
    if (state.isosurfaces) {
        checkRecords(r, *state.isosurfaces, edits.isosurfaces, "isosurface");
        for (size_t i = 0; i < edits.isosurfaces.size(); ++i) {
            edits.isosurfaces[i].isovalue = (*state.isosurfaces)[i].isovalue;
            changed.isosurfaces.insert(i);
        }
    }
    return changed;
}

}  // namespace ripple::apps
