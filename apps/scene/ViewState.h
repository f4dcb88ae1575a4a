// A view set up in ripple-view, saved as a small JSON file that ripple-render reads too, so the same view
// renders identically offline: the camera, the renderer settings, the image size and what the Lights and
// Volumes panels edited. The scene itself (a glTF file, --demo, --volume, --environment) stays on the
// command line: give both programs the same.
//
//   {
//     "ripple-view-state": 1,
//     "camera": {"type": "perspective", "position": [x, y, z], "direction": [x, y, z], "up": [x, y, z],
//                "fovy": 0.698},                      // or "type": "orthographic" with "height"
//     "renderer": {"subtype": "default", "pixelSamples": 1, "maxPathLength": 5, "ambientRadiance": 0.2,
//                  "background": [r, g, b, a], "traversal": "software"},
//     "size": [width, height],
//     "lights": [{"label": "sun", "color": [r, g, b], "intensity": 3, "direction": [x, y, z]},
//                {"label": "environment", "color": [1, 1, 1], "intensity": 1, "rotation": 90}],
//     "volumes": [{"label": "volume 0", "colorMap": "viridis", "colors": [[r, g, b], ...],
//                  "opacities": [a, ...], "valueRange": [lo, hi], "unitDistance": 1}],
//     "isosurfaces": [{"label": "isosurface 0", "isovalue": 0.5}]
//   }
//
// Every member but "ripple-view-state" and "camera" may be left out (the program's own setting stays). The
// scene's editable records (SceneEdits) must match "lights", "volumes" and "isosurfaces" where given: the
// same count and labels in the same order (applyViewEdits).
#pragma once

#include "apps/scene/AnariScene.h"
#include "apps/scene/SceneEdits.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace ripple::apps {

struct ViewState {
    CameraView camera;
    std::optional<std::string> renderer;       // the ANARI renderer subtype
    std::optional<int32_t> pixelSamples;       // per pass (ripple-view)
    std::optional<int32_t> maxPathLength;
    std::optional<float> ambientRadiance;
    std::optional<glm::vec4> background;
    std::optional<glm::uvec2> size;
    std::optional<std::string> traversal;      // the device parameter "traversal"
    // The panels' values (handles unset); each list only where the file has it.
    std::optional<std::vector<EditableLight>> lights;  // a light without "rotation" in the file: NaN (keeps the scene's)
    std::optional<std::vector<EditableVolume>> volumes;
    std::optional<std::vector<EditableIsosurface>> isosurfaces;
};

// Throws std::runtime_error naming the file and what is wrong: unreadable, not JSON, a missing or
// mistyped member, a non-finite or out-of-range number, a zero (or overflowing) direction or up.
ViewState readViewState(const std::filesystem::path& file);
// Throws std::runtime_error naming the file when it cannot be written.
void writeViewState(const std::filesystem::path& file, const ViewState& state);

// Copies the file's light, volume and iso-surface values into the scene's records and returns which changed
// (to be committed). They replace the scene's as built, including --environment-intensity and
// --environment-rotation (a light without "rotation" keeps its turn). `withLights`: whether this rank holds the scene's lights (under mpirun rank 0 alone
// does; elsewhere the file's lights are skipped). Throws naming the file when a list differs from the
// scene's in length or in a label.
SceneEditRequests applyViewEdits(const ViewState& state, SceneEdits& edits, bool withLights,
                                 const std::filesystem::path& file);

}  // namespace ripple::apps
