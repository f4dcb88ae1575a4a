// Reading and writing view-state files (see ViewState.h).
#include "apps/common/ViewState.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
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

}  // namespace

ViewState readViewState(const std::filesystem::path& file) {
    const Reader r(file.string());
    std::ifstream in(file, std::ios::binary);
    if (!in) r.fail("cannot open the view file");
    std::stringstream text;
    text << in.rdbuf();
    Json root;
    try {
        root = Json::parse(text.str());
    } catch (const Json::parse_error& e) {
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
    }
    if (const auto it = root.find("size"); it != root.end()) {
        if (!it->is_array() || it->size() != 2) r.fail("\"size\" must be [width, height]");
        state.size = glm::uvec2(uint32_t(r.integer((*it)[0], "size[0]", 1, 16384)), uint32_t(r.integer((*it)[1], "size[1]", 1, 16384)));
    }
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
    Json root = {{"ripple-view-state", kVersion}, {"camera", camera}, {"renderer", renderer}};
    if (state.size) root["size"] = {state.size->x, state.size->y};
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << root.dump(2) << "\n";
    if (!out) throw std::runtime_error(file.string() + ": cannot write the view file");
}

}  // namespace ripple::apps
