// Editable scene objects (see SceneEdits.h).
#include "apps/scene/SceneEdits.h"

#include "apps/scene/AnariParams.h"
#include "apps/scene/EnvironmentOptions.h"

#include <stdexcept>

namespace ripple::apps {
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

void SceneEdits::commit(const SceneEditRequests& requests) const {
    for (size_t i : requests.lights) commit(lights.at(i));
    for (size_t i : requests.volumes) commit(volumes.at(i));
    for (size_t i : requests.isosurfaces) commit(isosurfaces.at(i));
}

}  // namespace ripple::apps
