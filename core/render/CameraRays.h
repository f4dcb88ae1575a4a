// How a core::Camera becomes the camera fields of gpu::FrameConstants that pt_generate turns into rays:
// perspective (pinhole, or a thin lens for depth of field), orthographic, and omnidirectional
// (equirectangular: longitude across the image, latitude up it, the centre looking along `direction`).
#pragma once

#include "shaders/shared/path.h"

namespace ripple::core {

struct Camera;

// Fills cameraPosition, cameraForward, cameraRight, cameraUp and imageRegion. Throws std::invalid_argument
// naming what is wrong for a camera that cannot produce rays (NaN or Inf, zero direction, unknown kind,
// fovy outside (0, pi), height, aspect or focus distance not finite and positive, negative aperture).
void writeCamera(const Camera& camera, gpu::FrameConstants& frame);

}  // namespace ripple::core
