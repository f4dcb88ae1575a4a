// The viewer's camera moves as geometry: orbiting keeps the distance to the pivot and looks at it, a full
// turn comes back, pitch stops short of the poles, panning and flying move camera and pivot together, and
// zoom steps scale the distance by 0.9.
#include "apps/ripple-view/OrbitCamera.h"

#include <doctest/doctest.h>

#include <glm/glm.hpp>

using ripple::apps::CameraView;
using ripple::apps::OrbitCamera;

namespace {

OrbitCamera cameraAtFront() {
    CameraView view;
    view.position = {0.0f, 0.0f, 5.0f};
    view.direction = {0.0f, 0.0f, -1.0f};
    view.up = {0.0f, 1.0f, 0.0f};
    OrbitCamera camera;
    camera.reset(view, glm::vec3(-1.0f), glm::vec3(1.0f));
    return camera;
}

float distanceToPivot(const OrbitCamera& c) { return glm::length(c.view().position - c.pivot()); }

}  // namespace

TEST_CASE("orbit camera: the pivot is the point ahead nearest the bounds' centre") {
    const OrbitCamera camera = cameraAtFront();
    CHECK(glm::length(camera.pivot() - glm::vec3(0.0f)) < 1e-6f);
    CHECK(distanceToPivot(camera) == doctest::Approx(5.0f));
}

TEST_CASE("orbit camera: orbiting keeps the distance, looks at the pivot, and a full turn comes back") {
    OrbitCamera camera = cameraAtFront();
    camera.orbit(0.7f, 0.3f);
    CHECK(distanceToPivot(camera) == doctest::Approx(5.0f).epsilon(1e-5));
    const glm::vec3 toPivot = glm::normalize(camera.pivot() - camera.view().position);
    CHECK(glm::dot(toPivot, camera.view().direction) == doctest::Approx(1.0f).epsilon(1e-5));
    CHECK(camera.view().position.y > 0.0f);  // positive dy raises the camera
    camera.orbit(-0.7f, -0.3f);
    CHECK(glm::length(camera.view().position - glm::vec3(0.0f, 0.0f, 5.0f)) < 1e-4f);
    OrbitCamera turned = cameraAtFront();
    for (int i = 0; i < 8; ++i) turned.orbit(0.25f * 3.14159265f, 0.0f);
    CHECK(glm::length(turned.view().position - glm::vec3(0.0f, 0.0f, 5.0f)) < 1e-4f);
    OrbitCamera right = cameraAtFront();
    right.orbit(0.5f, 0.0f);
    CHECK(right.view().position.x < 0.0f);  // dragging right swings the camera left: the scene follows the cursor
}

TEST_CASE("orbit camera: pitch stops short of the poles") {
    OrbitCamera camera = cameraAtFront();
    camera.orbit(0.0f, 10.0f);
    const glm::vec3 toCamera = glm::normalize(camera.view().position - camera.pivot());
    CHECK(toCamera.y < 1.0f);
    CHECK(toCamera.y > 0.999f);
    CHECK(glm::length(glm::cross(camera.view().direction, camera.view().up)) > 1e-3f);  // up still defines a right axis
}

TEST_CASE("orbit camera: pan and fly move camera and pivot together; zoom scales the distance") {
    OrbitCamera camera = cameraAtFront();
    camera.pan(0.1f, 0.0f);
    CHECK(camera.view().position.x < 0.0f);
    CHECK(camera.pivot().x == doctest::Approx(camera.view().position.x));
    CHECK(distanceToPivot(camera) == doctest::Approx(5.0f));
    camera.fly(0.1f, 0.0f, 0.0f);
    CHECK(distanceToPivot(camera) == doctest::Approx(5.0f));
    CHECK(camera.view().position.z < 5.0f);
    camera.zoom(1.0f);
    CHECK(distanceToPivot(camera) == doctest::Approx(4.5f));
    camera.zoom(-1.0f);
    CHECK(distanceToPivot(camera) == doctest::Approx(5.0f));
}
