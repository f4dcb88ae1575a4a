// A view set up in ripple-view, saved as a small JSON file that ripple-render reads too, so the same view
// renders identically offline: the camera, the renderer settings and the image size.
//
//   {
//     "ripple-view-state": 1,
//     "camera": {"type": "perspective", "position": [x, y, z], "direction": [x, y, z], "up": [x, y, z],
//                "fovy": 0.698},                      // or "type": "orthographic" with "height"
//     "renderer": {"subtype": "default", "pixelSamples": 1, "maxPathLength": 5, "ambientRadiance": 0.2,
//                  "background": [r, g, b, a]},
//     "size": [width, height]
//   }
//
// Every member but "ripple-view-state" and "camera" may be left out (the program's own setting stays).
#pragma once

#include "apps/common/AnariScene.h"

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
};

// Throws std::runtime_error naming the file and what is wrong: unreadable, not JSON, a missing or
// mistyped member, a non-finite or out-of-range number, a zero (or overflowing) direction or up.
ViewState readViewState(const std::filesystem::path& file);
// Throws std::runtime_error naming the file when it cannot be written.
void writeViewState(const std::filesystem::path& file, const ViewState& state);

}  // namespace ripple::apps
