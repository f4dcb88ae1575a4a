// The viewer's camera controller: a CameraView moved by orbiting about a pivot, panning, zooming (dolly
// towards the pivot) and flying, with no window or ANARI code, so that its moves are plain geometry.
#pragma once

#include "apps/scene/AnariScene.h"

#include <glm/glm.hpp>

namespace ripple::apps {

class OrbitCamera {
public:
    // Starts at `view`, orbiting about the point on its line of sight nearest the bounds' centre (or one
    // unit ahead when that lies behind it); `lo`/`hi` set the speed of panning and flying.
    void reset(const CameraView& view, const glm::vec3& lo, const glm::vec3& hi);

    // Turns about the pivot: `dx` radians about the up vector, `dy` radians about the camera's right axis
    // (clamped short of the poles, so that up stays meaningful).
    void orbit(float dx, float dy);
    // Moves camera and pivot in the view plane by fractions of the view's height at the pivot.
    void pan(float dx, float dy);
    // Moves towards the pivot by the factor 0.9^steps of its distance (negative steps move away).
    void zoom(float steps);
    // Moves camera and pivot by `forward`, `right` and `up` scene units (scaled by the scene's size).
    void fly(float forward, float right, float up);

    const CameraView& view() const { return view_; }
    CameraView& view() { return view_; }
    glm::vec3 pivot() const { return pivot_; }

private:
    CameraView view_;
    glm::vec3 pivot_{0.0f};
    float sceneSize_ = 1.0f;
};

}  // namespace ripple::apps
