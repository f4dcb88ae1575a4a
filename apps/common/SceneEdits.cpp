// Editable scene objects and the environment light (see SceneEdits.h).
#include "apps/common/SceneEdits.h"

#include "apps/common/AnariParams.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace ripple::apps {
namespace {

glm::vec3 environmentDirection(float rotationDegrees) {
    const float turn = glm::radians(rotationDegrees);
    return {-std::sin(turn), 0.0f, -std::cos(turn)};
}

}  // namespace

const char* intensityParameter(const std::string& lightSubtype) {
    if (lightSubtype == "directional") return "irradiance";
    if (lightSubtype == "quad" || lightSubtype == "ring") return "radiance";
    if (lightSubtype == "hdri") return "scale";
    return "intensity";
}

SceneEdits::~SceneEdits() {
    for (const EditableLight& l : lights) anariRelease(device_, l.handle);
    for (const EditableVolume& v : volumes) anariRelease(device_, v.handle);
    for (const EditableIsosurface& i : isosurfaces) anariRelease(device_, i.handle);
}

void SceneEdits::add(EditableLight light) {
    anariRetain(device_, light.handle);
    lights.push_back(std::move(light));
}

void SceneEdits::add(EditableVolume volume) {
    anariRetain(device_, volume.handle);
    volume.sceneColors = volume.colors;
    volumes.push_back(std::move(volume));
}

void SceneEdits::add(EditableIsosurface isosurface) {
    anariRetain(device_, isosurface.handle);
    isosurfaces.push_back(std::move(isosurface));
}

void SceneEdits::commit(const EditableLight& light) const {
    if (light.subtype != "hdri") anari::set(device_, light.handle, "color", light.color);
    anari::set(device_, light.handle, intensityParameter(light.subtype), light.intensity);
    if (light.direction) anari::set(device_, light.handle, "direction", glm::normalize(*light.direction));
    if (light.subtype == "hdri") anari::set(device_, light.handle, "direction", environmentDirection(light.rotationDegrees));
    anariCommitParameters(device_, light.handle);
}

void SceneEdits::commit(const EditableVolume& volume) const {
    // New arrays each time (the volume holds them; a mapped array shared with a frame in flight would not do).
    ANARIArray1D colors = anari::newArray1D(device_, volume.colors), opacities = nullptr;
    try {
        opacities = anari::newArray1D(device_, volume.opacities);
    } catch (...) {
        anariRelease(device_, colors);
        throw;
    }
    anari::setObject(device_, volume.handle, "color", ANARI_ARRAY1D, colors);
    anari::setObject(device_, volume.handle, "opacity", ANARI_ARRAY1D, opacities);
    anariRelease(device_, colors);
    anariRelease(device_, opacities);
    anariSetParameter(device_, volume.handle, "valueRange", ANARI_FLOAT32_BOX1, &volume.valueRange.x);
    anari::set(device_, volume.handle, "unitDistance", volume.unitDistance);
    anariCommitParameters(device_, volume.handle);
}

void SceneEdits::commit(const EditableIsosurface& isosurface) const {
    anari::set(device_, isosurface.handle, "isovalue", isosurface.isovalue);
    anariCommitParameters(device_, isosurface.handle);
}

ANARILight newEnvironmentLight(ANARIDevice device, const LinearImage& image, float intensity, float rotationDegrees) {
    ANARILight light = anariNewLight(device, "hdri");
    if (!light) throw std::runtime_error("the device has no 'hdri' light: --environment needs one");
    ANARIArray2D radiance = anariNewArray2D(device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC3, image.width, image.height);
    if (!radiance) {
        anariRelease(device, light);
        throw std::runtime_error("the device could not make a " + std::to_string(image.width) + "x" +
                                 std::to_string(image.height) + " array for --environment");
    }
    void* texels = anariMapArray(device, radiance);
    if (!texels) {
        anariRelease(device, radiance);
        anariRelease(device, light);
        throw std::runtime_error("the device could not map the --environment array");
    }
    std::memcpy(texels, image.rgb.data(), image.rgb.size() * sizeof(float));
    anariUnmapArray(device, radiance);
    anari::setObject(device, light, "radiance", ANARI_ARRAY2D, radiance);
    anariRelease(device, radiance);  // the light holds it
    anari::set(device, light, "direction", environmentDirection(rotationDegrees));
    anari::set(device, light, "up", glm::vec3(0.0f, 1.0f, 0.0f));
    anari::set(device, light, "scale", intensity);
    anariCommitParameters(device, light);
    return light;
}

LinearImage readEnvironmentImage(const std::string& file) {
    LinearImage image = readLinearImage(file);
    for (float value : image.rgb)
        if (!std::isfinite(value) || value < 0.0f)
            throw std::runtime_error("--environment " + file +
                                     ": holds a negative, NaN or Inf radiance; give a linear image of radiances");
    if (image.width < 2 || image.height < 1)
        throw std::runtime_error("--environment " + file + ": the image is too small to be an environment");
    return image;
}

}  // namespace ripple::apps
