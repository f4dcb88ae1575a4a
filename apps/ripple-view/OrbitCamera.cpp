// Orbit, pan, zoom and fly moves of the viewer's camera (see OrbitCamera.h).
#include "apps/ripple-view/OrbitCamera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace ripple::apps {

void OrbitCamera::reset(const CameraView& view, const glm::vec3& lo, const glm::vec3& hi) {
    view_ = view;
    view_.direction = glm::normalize(view_.direction);
    view_.up = glm::normalize(view_.up);
    const bool empty = glm::any(glm::greaterThan(lo, hi));
    const glm::vec3 centre = empty ? view_.position + view_.direction : 0.5f * (lo + hi);
    sceneSize_ = empty ? 1.0f : std::max(glm::length(hi - lo), 1e-6f);
    const float ahead = glm::dot(centre - view_.position, view_.direction);
    pivot_ = view_.position + view_.direction * (ahead > 1e-6f ? ahead : sceneSize_ * 0.5f);
}

void OrbitCamera::orbit(float dx, float dy) {
    const glm::vec3 up = view_.up;
    glm::vec3 offset = view_.position - pivot_;
    const float distance = glm::length(offset);
    if (distance <= 0.0f) return;
    // Pitch first, kept 0.01 rad short of the poles.
    const glm::vec3 toCamera = offset / distance;
    const float elevation = std::asin(std::clamp(glm::dot(toCamera, up), -1.0f, 1.0f));
    const float limit = 1.5607963f;  // pi/2 - 0.01
    const float pitch = std::clamp(elevation + dy, -limit, limit) - elevation;
    const glm::vec3 right = glm::normalize(glm::cross(view_.direction, up));
    // Turning the offset by -pitch about right (= direction x up) raises it towards up.
    if (std::isfinite(right.x)) offset = glm::vec3(glm::rotate(glm::mat4(1.0f), -pitch, right) * glm::vec4(offset, 0.0f));
    offset = glm::vec3(glm::rotate(glm::mat4(1.0f), -dx, up) * glm::vec4(offset, 0.0f));
    view_.position = pivot_ + offset;
    view_.direction = glm::normalize(-offset);
}

void OrbitCamera::pan(float dx, float dy) {
    const glm::vec3 right = glm::normalize(glm::cross(view_.direction, view_.up));
    const glm::vec3 up = glm::cross(right, view_.direction);
    const float distance = glm::length(pivot_ - view_.position);
    const float height = view_.orthographic ? view_.height : 2.0f * distance * std::tan(0.5f * view_.fovy);
    const glm::vec3 move = (-dx * right + dy * up) * height;
    view_.position += move;
    pivot_ += move;
}

void OrbitCamera::zoom(float steps) {
    if (view_.orthographic) {
        view_.height *= std::pow(0.9f, steps);
        return;
    }
    const glm::vec3 offset = view_.position - pivot_;
    view_.position = pivot_ + offset * std::pow(0.9f, steps);
}

void OrbitCamera::fly(float forward, float right, float up) {
    const glm::vec3 side = glm::normalize(glm::cross(view_.direction, view_.up));
    const glm::vec3 move = (forward * view_.direction + right * side + up * view_.up) * sceneSize_;
    view_.position += move;
    pivot_ += move;
}

}  // namespace ripple::apps
