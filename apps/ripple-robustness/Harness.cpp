// The robustness cases' device: the Ripple ANARI library through the C API, its status messages kept,
// object helpers that release what they make, and one-call float renders.
#include "apps/ripple-robustness/Robustness.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace ripple::robustness {

Harness::Harness() {
    library_ = anariLoadLibrary("ripple", &Harness::onStatus, this);
    if (!library_) throw std::runtime_error("cannot load the ANARI library 'ripple' (libanari_library_ripple.so)");
    device_ = anariNewDevice(library_, "default");
    if (!device_) {
        anariUnloadLibrary(library_);
        throw std::runtime_error("the ANARI library 'ripple' created no device");
    }
}

Harness::~Harness() {
    for (auto it = objects_.rbegin(); it != objects_.rend(); ++it) anariRelease(device_, *it);
    anariRelease(device_, device_);
    anariUnloadLibrary(library_);
}

void Harness::onStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                       ANARIStatusCode, const char* message) {
    if (severity > ANARI_SEVERITY_WARNING) return;
    auto* harness = const_cast<Harness*>(static_cast<const Harness*>(user));
    std::lock_guard lock(harness->mutex_);
    harness->messages_.emplace_back(severity, message ? message : "");
    if (harness->messages_.back().second.find("Vulkan validation") != std::string::npos) ++harness->validationMessages_;
}

size_t Harness::validationMessages() const {
    std::lock_guard lock(mutex_);
    return validationMessages_;
}

std::vector<std::string> Harness::messages() const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> texts;
    for (const auto& m : messages_) texts.push_back(m.second);
    return texts;
}

size_t Harness::errorCount() const {
    std::lock_guard lock(mutex_);
    return size_t(std::count_if(messages_.begin(), messages_.end(),
                                [](const auto& m) { return m.first <= ANARI_SEVERITY_ERROR; }));
}

bool Harness::messagesContain(const std::string& fragment) const {
    std::lock_guard lock(mutex_);
    return std::any_of(messages_.begin(), messages_.end(),
                       [&](const auto& m) { return m.second.find(fragment) != std::string::npos; });
}

void Harness::clearMessages() {
    std::lock_guard lock(mutex_);
    messages_.clear();
}

ANARIMaterial Harness::matte(glm::vec3 color, float opacity) {
    ANARIMaterial material = keep(anariNewMaterial(device_, "matte"));
    anariSetParameter(device_, material, "color", ANARI_FLOAT32_VEC3, &color);
    anariSetParameter(device_, material, "opacity", ANARI_FLOAT32, &opacity);
    anariCommitParameters(device_, material);
    return material;
}

ANARISurface Harness::surface(ANARIGeometry geometry, ANARIMaterial material) {
    ANARISurface surface = keep(anariNewSurface(device_));
    anariSetParameter(device_, surface, "geometry", ANARI_GEOMETRY, &geometry);
    anariSetParameter(device_, surface, "material", ANARI_MATERIAL, &material);
    anariCommitParameters(device_, surface);
    return surface;
}

ANARIGeometry Harness::triangles(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& indices) {
    ANARIGeometry geometry = keep(anariNewGeometry(device_, "triangle"));
    ANARIArray1D vertices = array(ANARI_FLOAT32_VEC3, positions);
    anariSetParameter(device_, geometry, "vertex.position", ANARI_ARRAY1D, &vertices);
    if (!indices.empty()) {
        ANARIArray1D index = array(ANARI_UINT32_VEC3, indices);
        anariSetParameter(device_, geometry, "primitive.index", ANARI_ARRAY1D, &index);
    }
    anariCommitParameters(device_, geometry);
    return geometry;
}

ANARIGeometry Harness::spheres(const std::vector<glm::vec3>& centers, float radius) {
    ANARIGeometry geometry = keep(anariNewGeometry(device_, "sphere"));
    ANARIArray1D positions = array(ANARI_FLOAT32_VEC3, centers);
    anariSetParameter(device_, geometry, "vertex.position", ANARI_ARRAY1D, &positions);
    anariSetParameter(device_, geometry, "radius", ANARI_FLOAT32, &radius);
    anariCommitParameters(device_, geometry);
    return geometry;
}

ANARIGroup Harness::group(const std::vector<ANARISurface>& surfaces) {
    ANARIGroup group = keep(anariNewGroup(device_));
    ANARIArray1D list = array(ANARI_SURFACE, std::vector<ANARIObject>(surfaces.begin(), surfaces.end()));
    anariSetParameter(device_, group, "surface", ANARI_ARRAY1D, &list);
    anariCommitParameters(device_, group);
    return group;
}

ANARIInstance Harness::instance(ANARIGroup group, const glm::mat4& transform) {
    ANARIInstance instance = keep(anariNewInstance(device_, "transform"));
    anariSetParameter(device_, instance, "group", ANARI_GROUP, &group);
    anariSetParameter(device_, instance, "transform", ANARI_FLOAT32_MAT4, glm::value_ptr(transform));
    anariCommitParameters(device_, instance);
    return instance;
}

ANARIWorld Harness::world(const std::vector<ANARISurface>& surfaces, const std::vector<ANARIInstance>& instances,
                          const std::vector<ANARILight>& lights) {
    ANARIWorld world = keep(anariNewWorld(device_));
    if (!surfaces.empty()) {
        ANARIArray1D list = array(ANARI_SURFACE, std::vector<ANARIObject>(surfaces.begin(), surfaces.end()));
        anariSetParameter(device_, world, "surface", ANARI_ARRAY1D, &list);
    }
    if (!instances.empty()) {
        ANARIArray1D list = array(ANARI_INSTANCE, std::vector<ANARIObject>(instances.begin(), instances.end()));
        anariSetParameter(device_, world, "instance", ANARI_ARRAY1D, &list);
    }
    if (!lights.empty()) {
        ANARIArray1D list = array(ANARI_LIGHT, std::vector<ANARIObject>(lights.begin(), lights.end()));
        anariSetParameter(device_, world, "light", ANARI_ARRAY1D, &list);
    }
    anariCommitParameters(device_, world);
    return world;
}

ANARILight Harness::directional(glm::vec3 direction, float irradiance) {
    ANARILight light = keep(anariNewLight(device_, "directional"));
    anariSetParameter(device_, light, "direction", ANARI_FLOAT32_VEC3, &direction);
    anariSetParameter(device_, light, "irradiance", ANARI_FLOAT32, &irradiance);
    anariCommitParameters(device_, light);
    return light;
}

ANARICamera Harness::perspective(glm::vec3 position, glm::vec3 direction, glm::vec3 up, float fovy) {
    ANARICamera camera = keep(anariNewCamera(device_, "perspective"));
    anariSetParameter(device_, camera, "position", ANARI_FLOAT32_VEC3, &position);
    anariSetParameter(device_, camera, "direction", ANARI_FLOAT32_VEC3, &direction);
    anariSetParameter(device_, camera, "up", ANARI_FLOAT32_VEC3, &up);
    anariSetParameter(device_, camera, "fovy", ANARI_FLOAT32, &fovy);
    anariCommitParameters(device_, camera);
    return camera;
}

Image Harness::render(ANARIWorld world, ANARICamera camera, const RenderSettings& settings) {
    ANARIRenderer renderer = anariNewRenderer(device_, "default");
    anariSetParameter(device_, renderer, "pixelSamples", ANARI_INT32, &settings.pixelSamples);
    anariSetParameter(device_, renderer, "maxPathLength", ANARI_INT32, &settings.maxPathLength);
    anariSetParameter(device_, renderer, "background", ANARI_FLOAT32_VEC4, &settings.background);
    anariSetParameter(device_, renderer, "ambientRadiance", ANARI_FLOAT32, &settings.ambientRadiance);
    anariSetParameter(device_, renderer, "ambientColor", ANARI_FLOAT32_VEC3, &settings.ambientColor);
    anariCommitParameters(device_, renderer);

    const float aspect = float(settings.size.x) / float(settings.size.y);
    anariSetParameter(device_, camera, "aspect", ANARI_FLOAT32, &aspect);
    anariCommitParameters(device_, camera);

    Image image;
    ANARIFrame frame = anariNewFrame(device_);
    if (frame) {
        const ANARIDataType colorType = ANARI_FLOAT32_VEC4;
        anariSetParameter(device_, frame, "size", ANARI_UINT32_VEC2, &settings.size);
        anariSetParameter(device_, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
        anariSetParameter(device_, frame, "world", ANARI_WORLD, &world);
        anariSetParameter(device_, frame, "camera", ANARI_CAMERA, &camera);
        anariSetParameter(device_, frame, "renderer", ANARI_RENDERER, &renderer);
        anariCommitParameters(device_, frame);
        anariRenderFrame(device_, frame);
        anariFrameReady(device_, frame, ANARI_WAIT);
        ANARIDataType type = ANARI_UNKNOWN;
        const void* pixels = anariMapFrame(device_, frame, "channel.color", &image.width, &image.height, &type);
        if (pixels && type == ANARI_FLOAT32_VEC4 && image.width > 0 && image.height > 0) {
            const auto* values = static_cast<const glm::vec4*>(pixels);
            image.rgba.assign(values, values + size_t(image.width) * image.height);
            image.rendered = true;
            for (const glm::vec4& p : image.rgba)
                image.nonFinite += (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w)) ? 0 : 1;
        }
        if (pixels) anariUnmapFrame(device_, frame, "channel.color");
        anariRelease(device_, frame);
    }
    anariRelease(device_, renderer);
    return image;
}

Uniformity uniformity(const Image& image, float value, float tolerance) {
    Uniformity u;
    if (image.rgba.empty()) return u;
    double sum = 0.0;
    for (const glm::vec4& p : image.rgba) {
        bool outlier = false;
        for (int c = 0; c < 3; ++c) {
            const double deviation = std::abs(double(p[c]) - double(value));
            sum += double(p[c]);
            // NaN compares false everywhere: count it as an outlier explicitly.
            if (!(deviation <= double(tolerance))) outlier = true;
            if (std::isfinite(deviation)) u.maxDeviation = std::max(u.maxDeviation, deviation);
            else u.maxDeviation = INFINITY;
        }
        u.outliers += outlier ? 1 : 0;
    }
    u.mean = sum / (3.0 * double(image.rgba.size()));
    return u;
}

float maxRgbDifference(const Image& a, const Image& b) {
    if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return std::numeric_limits<float>::infinity();
    float largest = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); ++i)
        for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(a.rgba[i][c] - b.rgba[i][c]));
    return largest;
}

std::string formatNumber(double value, int digits) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.*g", digits, value);
    return text;
}

}  // namespace ripple::robustness
