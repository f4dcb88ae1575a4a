// Camera validation and the screen vectors pt_generate reads (see CameraRays.h).
#include "core/render/CameraRays.h"

#include "core/render/PathTracer.h"

#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ripple::core {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool positive(float x) { return std::isfinite(x) && x > 0.0f; }

}  // namespace

void writeCamera(const Camera& camera, gpu::FrameConstants& f) {
    auto reject = [](const std::string& why) { throw std::invalid_argument("PathTracer: camera " + why); };
    if (!finite(camera.position) || !finite(camera.direction) || !finite(camera.up)) reject("position, direction or up is NaN or Inf");
    if (glm::length(camera.direction) == 0.0f) reject("direction is zero");
    if (!positive(camera.aspect)) reject("aspect must be finite and positive");
    using Kind = Camera::Kind;
    if (camera.kind != Kind::Perspective && camera.kind != Kind::Orthographic && camera.kind != Kind::Omnidirectional)
        reject("kind is unknown");
    if (camera.kind == Kind::Orthographic && !positive(camera.height)) reject("height must be finite and positive");
    if (camera.kind == Kind::Perspective && !(camera.fovy > 0.0f && camera.fovy < 3.14159f)) reject("fovy must be in (0, pi)");
    if (!(std::isfinite(camera.apertureRadius) && camera.apertureRadius >= 0.0f)) reject("apertureRadius must be finite and >= 0");
    if (camera.apertureRadius > 0.0f && !positive(camera.focusDistance)) reject("focusDistance must be finite and positive");
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(camera.imageRegion[i])) reject("imageRegion is NaN or Inf");
    if (!(camera.nearClip >= 0.0f && std::isfinite(camera.nearClip) && camera.farClip > camera.nearClip))
        reject("near must be finite and >= 0, and far greater than near");

    const glm::vec3 forward = glm::normalize(camera.direction);
    glm::vec3 right = glm::cross(forward, camera.up);
    if (glm::length(right) < 1e-6f * glm::length(camera.up)) {  // up along the view: any perpendicular will do
        const glm::vec3 a = glm::abs(forward);
        right = glm::cross(forward, a.x < a.y && a.x < a.z ? glm::vec3(1, 0, 0) : a.y < a.z ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1));
    }
    right = glm::normalize(right);
    const glm::vec3 up = glm::cross(right, forward);

    // Half the screen's height: at unit distance for perspective, in world units for orthographic.
    float halfHeight = 1.0f;
    uint32_t kind = gpu::CAMERA_OMNIDIRECTIONAL;
    if (camera.kind == Kind::Perspective) {
        halfHeight = std::tan(0.5f * camera.fovy);
        kind = gpu::CAMERA_PERSPECTIVE;
    } else if (camera.kind == Kind::Orthographic) {
        halfHeight = 0.5f * camera.height;
        kind = gpu::CAMERA_ORTHOGRAPHIC;
    }
    const float halfWidth = camera.kind == Kind::Omnidirectional ? 1.0f : halfHeight * camera.aspect;
    const bool lens = camera.kind == Kind::Perspective && camera.apertureRadius > 0.0f;
    f.cameraPosition = gpu::vec4(camera.position, std::bit_cast<float>(kind));
    f.cameraForward = gpu::vec4(forward, lens ? camera.apertureRadius : 0.0f);
    f.cameraRight = gpu::vec4(halfWidth * right, lens ? camera.focusDistance : 1.0f);
    const bool clips = camera.kind != Kind::Omnidirectional;
    f.cameraUp = gpu::vec4(halfHeight * up, clips ? camera.nearClip : 0.0f);
    f.imageRegion = camera.imageRegion;
    f.cameraFar = clips ? camera.farClip : std::numeric_limits<float>::infinity();
}

}  // namespace ripple::core
