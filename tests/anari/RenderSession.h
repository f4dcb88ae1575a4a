// What the render tests share: a device loaded through the public C API with its status messages
// collected, small helpers to build objects, rendering a frame to linear float pixels, and comparing an
// image with a stored reference PNG (RIPPLE_UPDATE_REFERENCES=1 rewrites the references instead).
#pragma once

#include "anari/anari.h"
#include "tests/support/StatusLog.h"

#include <glm/glm.hpp>

#include <cstring>
#include <set>
#include <string>
#include <vector>

namespace ripple::test {

// Pixels as the frame maps them: row 0 at the bottom. `linear` holds linear RGBA whatever channel type
// was rendered; `srgb8` the 8-bit sRGB bytes when the colour channel was UFIXED8_RGBA_SRGB.
struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec4> linear;
    std::vector<uint8_t> srgb8;
    std::vector<float> depth;
    const glm::vec4& at(uint32_t x, uint32_t y) const { return linear[size_t(y) * width + x]; }
};

class RenderSession {
public:
    // libraryName: the ANARI library to load (the compositing tests load "ripple_ptc" through the same helpers).
    explicit RenderSession(const char* libraryName = "ripple");
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    StatusLog log;
    ANARIDevice device = nullptr;

    // Every object made through these helpers is released when the session ends.
    template <class Handle>
    Handle keep(Handle handle) {
        objects_.push_back(handle);
        return handle;
    }

    void set(ANARIObject object, const char* name, float value) { setRaw(object, name, ANARI_FLOAT32, &value); }
    void set(ANARIObject object, const char* name, glm::vec3 value) {
        setRaw(object, name, ANARI_FLOAT32_VEC3, &value);
    }
    void set(ANARIObject object, const char* name, glm::vec4 value) {
        setRaw(object, name, ANARI_FLOAT32_VEC4, &value);
    }
    void set(ANARIObject object, const char* name, glm::uvec2 value) {
        setRaw(object, name, ANARI_UINT32_VEC2, &value);
    }
    void set(ANARIObject object, const char* name, const char* value) { setRaw(object, name, ANARI_STRING, value); }
    void setInt(ANARIObject object, const char* name, int32_t value) { setRaw(object, name, ANARI_INT32, &value); }
    void setObject(ANARIObject object, const char* name, ANARIDataType type, ANARIObject value) {
        setRaw(object, name, type, &value);
    }
    void setRaw(ANARIObject object, const char* name, ANARIDataType type, const void* value) {
        anariSetParameter(device, object, name, type, value);
    }
    void commit(ANARIObject object) { anariCommitParameters(device, object); }

    // A managed 1D array holding a copy of `values` (elementType must match T's layout).
    template <class T>
    ANARIArray1D array(ANARIDataType elementType, const std::vector<T>& values) {
        ANARIArray1D array = keep(anariNewArray1D(device, nullptr, nullptr, nullptr, elementType, values.size()));
        std::memcpy(anariMapArray(device, array), values.data(), values.size() * sizeof(T));
        anariUnmapArray(device, array);
        return array;
    }
    ANARIArray1D objects(ANARIDataType elementType, const std::vector<ANARIObject>& handles) {
        return array(elementType, handles);
    }

    ANARIMaterial matte(glm::vec3 color);
    ANARIMaterial matteFromAttribute();  // color = the geometry's "color" attribute
    ANARISurface surface(ANARIGeometry geometry, ANARIMaterial material);
    // A square floor at y = 0, 6 units wide, as two indexed triangles.
    ANARIGeometry floor();
    // A blue matte sphere (radius 0.6, centre (0, 0.6, 0)) on the grey floor under a directional light.
    ANARIWorld sphereOnFloor();
    ANARILight directional(glm::vec3 direction, float irradiance);
    ANARICamera perspective(glm::vec3 position, glm::vec3 target);
    // Parallel rays along `direction` from a view `height` units tall around `position`; up the default (0, 1, 0).
    ANARICamera orthographic(glm::vec3 position, glm::vec3 direction, float height = 1.0f);
    ANARIRenderer renderer(int32_t pixelSamples, int32_t maxPathLength, glm::vec4 background = {0.1f, 0.1f, 0.15f, 1});
    ANARIWorld world(const std::vector<ANARISurface>& surfaces, const std::vector<ANARILight>& lights);
    ANARIFrame frame(ANARIWorld world, ANARICamera camera, ANARIRenderer renderer, glm::uvec2 size,
                     ANARIDataType colorType, bool depth = false);

    // Renders once (waiting for the worker) and maps the channels the frame has.
    Image render(ANARIFrame frame);
    // Maps the channels of a frame already rendered (data-parallel: only rank 0 holds the image).
    Image mapped(ANARIFrame frame);
    uint32_t numSamples(ANARIFrame frame);
    uint64_t sceneBuilds(ANARIFrame frame);

private:
    ANARILibrary library_ = nullptr;
    std::vector<ANARIObject> objects_;
    std::set<ANARIFrame> framesWithDepth_;
};

// Root mean square difference over the linear RGB of all pixels.
double rmseRgb(const Image& a, const Image& b);

// Compares an sRGB-rendered image with references/<name>.png by rmseRgb; with RIPPLE_UPDATE_REFERENCES=1
// writes the reference instead. Above `threshold`, the rendered image is written to the working directory
// as <name>.actual.png for a look. Returns the RMSE (0 when updating).
double compareWithReference(const std::string& name, const Image& rendered, double threshold);

}  // namespace ripple::test
