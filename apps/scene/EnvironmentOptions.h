// --environment FILE with --environment-intensity and --environment-rotation, as ripple-render and
// ripple-view take them, and the "hdri" light they make.
#pragma once

#include "io/image/ImageIO.h"

#include <anari/anari.h>

#include <CLI/CLI.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <string>

namespace ripple::apps {

class SceneEdits;

struct EnvironmentOptions {
    std::string file;                   // equirectangular .hdr/.exr/.pfm/.png image; empty: none
    float intensity = 1.0f;             // the light's "scale"
    float rotationDegrees = 0.0f;       // its turn about the up axis (+Y)
};

// Adds --environment, --environment-intensity and --environment-rotation to `app`.
void addEnvironmentOptions(CLI::App& app, EnvironmentOptions& options);

// The image the options name, checked: finite, non-negative radiances, at least 2x1 texels; nothing without
// --environment. Throws naming the option or the file (also for a rotation that is not finite).
std::optional<LinearImage> readEnvironment(const EnvironmentOptions& options);

// The direction an "hdri" light turned by `rotationDegrees` about +Y faces (see newEnvironmentLight).
glm::vec3 environmentDirection(float rotationDegrees);

// An "hdri" light of an equirectangular image of linear radiances (row 0 at the top, towards +Y): its centre
// column is seen along -Z turned by `rotationDegrees` about +Y, so the default faces a camera looking down
// -Z. The caller releases the light; `edits`, where given, lists it as the light "environment". Throws when
// the device has no hdri light or cannot hold the image.
ANARILight newEnvironmentLight(ANARIDevice device, const LinearImage& image, float intensity, float rotationDegrees,
                               SceneEdits* edits = nullptr);

}  // namespace ripple::apps
