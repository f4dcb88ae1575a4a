// The --environment options and the hdri light (see EnvironmentOptions.h).
#include "apps/scene/EnvironmentOptions.h"

#include "apps/scene/AnariParams.h"
#include "apps/scene/SceneEdits.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace ripple::apps {

void addEnvironmentOptions(CLI::App& app, EnvironmentOptions& options) {
    app.add_option("--environment", options.file,
                   "equirectangular environment image lighting the scene (.hdr, .exr, .pfm, .png; linear radiance, the "
                   "image's top row up, +Y); it replaces the scene's ambient fill");
    app.add_option("--environment-intensity", options.intensity, "scale of the environment's radiance")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    app.add_option("--environment-rotation", options.rotationDegrees,
                   "turn of the environment about the up axis, degrees")->capture_default_str();
}

std::optional<LinearImage> readEnvironment(const EnvironmentOptions& options) {
    if (!std::isfinite(options.rotationDegrees)) throw std::runtime_error("--environment-rotation must be finite");
    if (options.file.empty()) return std::nullopt;
    LinearImage image = readLinearImage(options.file);
    for (float value : image.rgb)
        if (!std::isfinite(value) || value < 0.0f)
            throw std::runtime_error("--environment " + options.file +
                                     ": holds a negative, NaN or Inf radiance; give a linear image of radiances");
    if (image.width < 2 || image.height < 1)
        throw std::runtime_error("--environment " + options.file + ": the image is too small to be an environment");
    return image;
}

glm::vec3 environmentDirection(float rotationDegrees) {
    const float turn = glm::radians(rotationDegrees);
    return {-std::sin(turn), 0.0f, -std::cos(turn)};
}

ANARILight newEnvironmentLight(ANARIDevice device, const LinearImage& image, float intensity, float rotationDegrees,
                               SceneEdits* edits) {
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
    if (edits) edits->add({light, "environment", "hdri", glm::vec3(1.0f), intensity, std::nullopt, rotationDegrees});
    return light;
}

}  // namespace ripple::apps
