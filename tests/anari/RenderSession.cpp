// Device session, scene helpers, frame readback and reference comparison for the render tests.
#include "tests/anari/RenderSession.h"

#include "io/image/ImageIO.h"

#include <doctest/doctest.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace ripple::test {
namespace {

float srgbToLinear(uint8_t byte) {
    const float c = float(byte) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::vector<glm::vec4> decodeSrgb(const uint8_t* bytes, size_t pixels) {
    std::vector<glm::vec4> linear(pixels);
    for (size_t i = 0; i < pixels; ++i)
        linear[i] = glm::vec4(srgbToLinear(bytes[4 * i]), srgbToLinear(bytes[4 * i + 1]),
                              srgbToLinear(bytes[4 * i + 2]), float(bytes[4 * i + 3]) / 255.0f);
    return linear;
}

}  // namespace

RenderSession::RenderSession(const char* libraryName) {
    library_ = anariLoadLibrary(libraryName, &StatusLog::callback, &log);
    REQUIRE_MESSAGE(library_, log.dump());
    device = anariNewDevice(library_, "default");
    REQUIRE(device);
}

RenderSession::~RenderSession() {
    // Validation runs inside the device, which reports what it says as an error: none may appear.
    CHECK_MESSAGE(log.count({"Vulkan validation"}) == 0, log.dump());
    // Frames first: they may still render with everything else.
    for (auto it = objects_.rbegin(); it != objects_.rend(); ++it) anariRelease(device, *it);
    anariRelease(device, device);
    anariUnloadLibrary(library_);
}

ANARIMaterial RenderSession::matte(glm::vec3 color) {
    ANARIMaterial material = keep(anariNewMaterial(device, "matte"));
    set(material, "color", color);
    commit(material);
    return material;
}

ANARIMaterial RenderSession::matteFromAttribute() {
    ANARIMaterial material = keep(anariNewMaterial(device, "matte"));
    set(material, "color", "color");
    commit(material);
    return material;
}

ANARISurface RenderSession::surface(ANARIGeometry geometry, ANARIMaterial material) {
    ANARISurface surface = keep(anariNewSurface(device));
    setObject(surface, "geometry", ANARI_GEOMETRY, geometry);
    setObject(surface, "material", ANARI_MATERIAL, material);
    commit(surface);
    return surface;
}

ANARIGeometry RenderSession::floor() {
    ANARIGeometry geometry = keep(anariNewGeometry(device, "triangle"));
    const std::vector<glm::vec3> positions = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}};
    const std::vector<glm::uvec3> triangles = {{0, 2, 1}, {0, 3, 2}};
    setObject(geometry, "vertex.position", ANARI_ARRAY1D, array(ANARI_FLOAT32_VEC3, positions));
    setObject(geometry, "primitive.index", ANARI_ARRAY1D, array(ANARI_UINT32_VEC3, triangles));
    commit(geometry);
    return geometry;
}

ANARIWorld RenderSession::sphereOnFloor() {
    ANARIGeometry sphere = keep(anariNewGeometry(device, "sphere"));
    setObject(sphere, "vertex.position", ANARI_ARRAY1D, array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0.0f, 0.6f, 0.0f}}));
    set(sphere, "radius", 0.6f);
    commit(sphere);
    return world({surface(sphere, matte({0.2f, 0.5f, 0.8f})), surface(floor(), matte(glm::vec3(0.7f)))},
                 {directional(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.4f)), 3.0f)});
}

ANARILight RenderSession::directional(glm::vec3 direction, float irradiance) {
    ANARILight light = keep(anariNewLight(device, "directional"));
    set(light, "direction", direction);
    set(light, "irradiance", irradiance);
    commit(light);
    return light;
}

ANARICamera RenderSession::perspective(glm::vec3 position, glm::vec3 target) {
    ANARICamera camera = keep(anariNewCamera(device, "perspective"));
    set(camera, "position", position);
    set(camera, "direction", target - position);
    set(camera, "up", glm::vec3(0, 1, 0));
    set(camera, "fovy", 0.8f);
    commit(camera);
    return camera;
}

ANARICamera RenderSession::orthographic(glm::vec3 position, glm::vec3 direction, float height) {
    ANARICamera camera = keep(anariNewCamera(device, "orthographic"));
    set(camera, "position", position);
    set(camera, "direction", direction);
    set(camera, "height", height);
    commit(camera);
    return camera;
}

ANARIRenderer RenderSession::renderer(int32_t pixelSamples, int32_t maxPathLength, glm::vec4 background) {
    ANARIRenderer renderer = keep(anariNewRenderer(device, "default"));
    setInt(renderer, "pixelSamples", pixelSamples);
    setInt(renderer, "maxPathLength", maxPathLength);
    set(renderer, "background", background);
    commit(renderer);
    return renderer;
}

ANARIWorld RenderSession::world(const std::vector<ANARISurface>& surfaces, const std::vector<ANARILight>& lights) {
    ANARIWorld world = keep(anariNewWorld(device));
    if (!surfaces.empty())
        setObject(world, "surface", ANARI_ARRAY1D,
                  objects(ANARI_SURFACE, std::vector<ANARIObject>(surfaces.begin(), surfaces.end())));
    if (!lights.empty())
        setObject(world, "light", ANARI_ARRAY1D,
                  objects(ANARI_LIGHT, std::vector<ANARIObject>(lights.begin(), lights.end())));
    commit(world);
    return world;
}

ANARIFrame RenderSession::frame(ANARIWorld world, ANARICamera camera, ANARIRenderer renderer, glm::uvec2 size,
                                ANARIDataType colorType, bool depth) {
    ANARIFrame frame = keep(anariNewFrame(device));
    setObject(frame, "world", ANARI_WORLD, world);
    setObject(frame, "camera", ANARI_CAMERA, camera);
    setObject(frame, "renderer", ANARI_RENDERER, renderer);
    set(frame, "size", size);
    setRaw(frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    if (depth) {
        const ANARIDataType depthType = ANARI_FLOAT32;
        setRaw(frame, "channel.depth", ANARI_DATA_TYPE, &depthType);
        framesWithDepth_.insert(frame);
    }
    commit(frame);
    return frame;
}

Image RenderSession::render(ANARIFrame frame) {
    anariRenderFrame(device, frame);
    REQUIRE(anariFrameReady(device, frame, ANARI_WAIT) == 1);
    return mapped(frame);
}

Image RenderSession::mapped(ANARIFrame frame) {
    Image image;
    ANARIDataType type = ANARI_UNKNOWN;
    const void* color = anariMapFrame(device, frame, "channel.color", &image.width, &image.height, &type);
    REQUIRE_MESSAGE(color, log.dump());
    const size_t pixels = size_t(image.width) * image.height;
    if (type == ANARI_FLOAT32_VEC4) {
        const auto* values = static_cast<const glm::vec4*>(color);
        image.linear.assign(values, values + pixels);
    } else {
        REQUIRE(type == ANARI_UFIXED8_RGBA_SRGB);
        const auto* bytes = static_cast<const uint8_t*>(color);
        image.srgb8.assign(bytes, bytes + 4 * pixels);
        image.linear = decodeSrgb(bytes, pixels);
    }
    anariUnmapFrame(device, frame, "channel.color");

    if (framesWithDepth_.count(frame)) {
        uint32_t width = 0, height = 0;
        const void* depth = anariMapFrame(device, frame, "channel.depth", &width, &height, &type);
        REQUIRE_MESSAGE(depth, log.dump());
        CHECK(type == ANARI_FLOAT32);
        const auto* values = static_cast<const float*>(depth);
        image.depth.assign(values, values + size_t(width) * height);
        anariUnmapFrame(device, frame, "channel.depth");
    }
    return image;
}

uint32_t RenderSession::numSamples(ANARIFrame frame) {
    uint32_t samples = 0;
    REQUIRE(anariGetProperty(device, frame, "numSamples", ANARI_UINT32, &samples, sizeof(samples), ANARI_WAIT) == 1);
    return samples;
}

uint64_t RenderSession::sceneBuilds(ANARIFrame frame) {
    uint64_t builds = 0;
    REQUIRE(anariGetProperty(device, frame, "ripple.sceneBuilds", ANARI_UINT64, &builds, sizeof(builds), ANARI_WAIT) ==
            1);
    return builds;
}

double rmseRgb(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    double sum = 0.0;
    for (size_t i = 0; i < a.linear.size(); ++i) {
        const glm::vec3 d = glm::vec3(a.linear[i]) - glm::vec3(b.linear[i]);
        sum += double(glm::dot(d, d));
    }
    return std::sqrt(sum / (3.0 * double(std::max<size_t>(a.linear.size(), 1))));
}

double compareWithReference(const std::string& name, const Image& rendered, double threshold) {
    REQUIRE(!rendered.srgb8.empty());
    const std::filesystem::path reference = std::filesystem::path(RIPPLE_REFERENCE_DIR) / (name + ".png");
    const char* update = std::getenv("RIPPLE_UPDATE_REFERENCES");
    if (update && std::string(update) == "1") {
        apps::writePngBottomUp(reference, rendered.width, rendered.height, rendered.srgb8.data());
        MESSAGE("wrote " << reference.string());
        return 0.0;
    }

    int width = 0, height = 0, channels = 0;
    uint8_t* pixels = stbi_load(reference.string().c_str(), &width, &height, &channels, 4);
    REQUIRE_MESSAGE(pixels, "missing reference " << reference.string() << " (RIPPLE_UPDATE_REFERENCES=1 makes it)");
    Image expected;
    expected.width = uint32_t(width);
    expected.height = uint32_t(height);
    // PNG rows run top to bottom; frames start at the bottom.
    std::vector<uint8_t> bottomUp(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        std::memcpy(&bottomUp[size_t(y) * width * 4], pixels + size_t(height - 1 - y) * width * 4, size_t(width) * 4);
    stbi_image_free(pixels);
    expected.linear = decodeSrgb(bottomUp.data(), size_t(width) * height);

    const double rmse = rmseRgb(rendered, expected);
    MESSAGE(name << ": RMSE " << rmse);
    if (rmse > threshold)
        apps::writePngBottomUp(name + ".actual.png", rendered.width, rendered.height, rendered.srgb8.data());
    return rmse;
}

}  // namespace ripple::test
