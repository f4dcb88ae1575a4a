// The robustness matrix: stiff and extreme inputs rendered through the Ripple ANARI device, one table row a
// case. The same cases run as tests (tests/robustness) and as the ripple-robustness program, which prints
// the table that docs/robustness.md keeps.
#pragma once

#include "anari/anari.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace ripple::robustness {

// One case's outcome. `expected` is decided BEFORE rendering, from a stated precision argument (for
// example: a translation more than 2^17 times the object's size leaves fewer than 6 bits of float
// mantissa for its surface), never from the result; the tests require holds where expected, and finite
// pixels always.
struct Row {
    std::string group;      // "scale x translation", "self-intersection", "radiometry", "sizes", "bad data", ...
    std::string name;       // e.g. "sphere, scale 1e-6, translation 1e7"
    bool expected = true;   // the tolerance should hold here
    bool holds = false;     // what was measured is within the tolerance
    bool finite = true;     // no NaN or Inf pixel
    std::string measured;   // the numbers, e.g. "mean 0.498 (want 0.500 +- 0.010)"
    std::string why;        // why it does not hold here, or how bad input was refused
};

// A float image as the frame maps it: RGBA, row 0 at the bottom.
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> rgba;
    uint64_t nonFinite = 0;  // pixels with a NaN or Inf component
    bool rendered = false;   // false when the device gave no frame (refused, with a message)
};

// What a render uses besides world and camera.
struct RenderSettings {
    glm::uvec2 size{32, 32};
    int32_t pixelSamples = 16;
    int32_t maxPathLength = 5;
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
    float ambientRadiance = 0.0f;
    glm::vec3 ambientColor{1.0f};
};

// A Ripple device loaded through the ANARI C API with its status messages recorded, helpers that make
// (and release at the end) the usual objects, and a one-call render to float pixels. Throws
// std::runtime_error when the library cannot be loaded. Not thread-safe apart from the status log.
class Harness {
public:
    Harness();
    ~Harness();
    Harness(const Harness&) = delete;
    Harness& operator=(const Harness&) = delete;

    ANARIDevice device() const { return device_; }

    // Every object made through the helpers (or passed to keep) is released when the harness ends.
    template <class Handle>
    Handle keep(Handle handle) {
        if (handle) objects_.push_back(handle);
        return handle;
    }
    // A managed 1D array holding a copy of `values` (elementType must match T's layout).
    template <class T>
    ANARIArray1D array(ANARIDataType elementType, const std::vector<T>& values) {
        ANARIArray1D a = keep(anariNewArray1D(device_, nullptr, nullptr, nullptr, elementType, values.size()));
        if (!values.empty()) std::memcpy(anariMapArray(device_, a), values.data(), values.size() * sizeof(T));
        anariUnmapArray(device_, a);
        return a;
    }
    ANARIMaterial matte(glm::vec3 color, float opacity = 1.0f);
    ANARISurface surface(ANARIGeometry geometry, ANARIMaterial material);
    ANARIGeometry triangles(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& indices);
    ANARIGeometry spheres(const std::vector<glm::vec3>& centers, float radius);
    ANARIGroup group(const std::vector<ANARISurface>& surfaces);
    ANARIInstance instance(ANARIGroup group, const glm::mat4& transform);
    // A world of surfaces, instances and lights (any may be empty).
    ANARIWorld world(const std::vector<ANARISurface>& surfaces, const std::vector<ANARIInstance>& instances,
                     const std::vector<ANARILight>& lights);
    ANARILight directional(glm::vec3 direction, float irradiance);
    ANARICamera perspective(glm::vec3 position, glm::vec3 direction, glm::vec3 up, float fovy);

    // Renders once, waiting for the frame, and maps channel.color as FLOAT32_VEC4 (linear). The frame is
    // released afterwards. An image with rendered == false when the device refused (see messages()).
    Image render(ANARIWorld world, ANARICamera camera, const RenderSettings& settings);

    // Status messages of severity WARNING or worse, since the last clearMessages().
    std::vector<std::string> messages() const;
    size_t errorCount() const;  // of those, ERROR or worse
    bool messagesContain(const std::string& fragment) const;
    void clearMessages();
    // Vulkan validation messages the device reported over the harness's life (clearMessages keeps them).
    size_t validationMessages() const;

private:
    static void onStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                         ANARIStatusCode, const char* message);

    ANARILibrary library_ = nullptr;
    ANARIDevice device_ = nullptr;
    std::vector<ANARIObject> objects_;
    mutable std::mutex mutex_;
    std::vector<std::pair<ANARIStatusSeverity, std::string>> messages_;
    size_t validationMessages_ = 0;
};

// Image statistics the cases share: mean of the RGB channels over the pixels, their largest distance
// from `value`, and how many pixels differ from `value` by more than `tolerance` in any channel.
struct Uniformity {
    double mean = 0.0;
    double maxDeviation = 0.0;
    uint64_t outliers = 0;
};
Uniformity uniformity(const Image& image, float value, float tolerance);
// The largest difference of any RGB channel of any pixel; infinite when the sizes differ or one is empty.
float maxRgbDifference(const Image& a, const Image& b);
// A number for the table: `digits` significant digits (printf's %g).
std::string formatNumber(double value, int digits = 2);

// The case groups, one file each. quick: the smaller sweep the tests run (the program runs the full one).
std::vector<Row> precisionCases(Harness& harness, bool quick);       // PrecisionCases.cpp: scale x translation
std::vector<Row> intersectionCases(Harness& harness, bool quick);    // IntersectionCases.cpp: acne, thin, degenerate
std::vector<Row> radiometryCases(Harness& harness, bool quick);      // RadiometryCases.cpp: 1e-10..1e10, sun, tiny emitters
std::vector<Row> extremeSizeCases(Harness& harness, bool quick);     // ExtremeSizeCases.cpp: frames, spp, fov, cameras
std::vector<Row> badDataCases(Harness& harness, bool quick);         // BadDataCases.cpp: NaN/Inf, indices, types
std::vector<Row> misuseCases(Harness& harness, bool quick);          // MisuseCases.cpp: sizes, releases, handles

}  // namespace ripple::robustness
