// A GltfScene turned into ANARI objects on any device (standard KHR object types and parameters only), and
// the camera helpers every scene source shares.
#pragma once

#include "io/gltf/GltfScene.h"

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace ripple::apps {

class SceneEdits;

// The apparent diameter of the studio key light that lights a scene without lights: the sun's, 0.53
// degrees, in radians (scripts/cycles_render.py gives Cycles' sun the same).
inline constexpr float kStudioSunAngularDiameter = 0.00925f;

// A viewpoint, independent of ANARI and of the image size.
struct CameraView {
    std::string name;
    bool orthographic = false;
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy = 0.6981317f;            // perspective: vertical field of view, radians (40 degrees)
    float height = 1.0f;                // orthographic: height of the view
    // Perspective: depth of field. A lens of this radius (0: a pinhole, everything sharp) focused at this
    // distance along `direction`.
    float apertureRadius = 0.0f;
    float focusDistance = 1.0f;
};

// What a scene source hands the renderer: a committed world (the caller releases it), the cameras the
// scene defines, and its bounds as the source knows them.
struct AnariWorld {
    ANARIWorld world = nullptr;
    std::vector<CameraView> cameras;
    glm::vec3 boundsMin{0.0f};
    glm::vec3 boundsMax{-1.0f};         // min > max: nothing drawn
    // Renderer settings that suit the scene: the uniform ambient light (W/sr/m^2) and the background.
    float ambientRadiance = 0.0f;
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
};

// One ANARI triangle geometry per GltfGeometry, one surface per geometry and material, one group per glTF
// mesh, one "transform" instance per node drawing a mesh, lights in the world. Texture coordinates go to
// vertex.attribute0, which the image2D samplers read. glTF light intensities are passed on unchanged (lux
// as W/m^2, candela as W/sr). A scene with neither lights nor untextured emissive materials gets a key
// directional light and an ambient fill, so that it is not black. Throws std::runtime_error when the
// device returns no object. withLights false: the world gets no lights, while the ambient fill and the
// background are chosen as with them (a data-parallel rank whose lights another rank holds). extraLights
// (an environment, say; the caller keeps them) count as the scene's lights. edits: where given, the lights
// this world holds are listed there (a viewer's light panel edits them).
AnariWorld buildAnariWorld(ANARIDevice device, const GltfScene& scene, bool withLights = true,
                           const std::vector<ANARILight>& extraLights = {}, SceneEdits* edits = nullptr);

// The glTF camera as a CameraView (node transform applied; orthographic height is twice ymag).
CameraView cameraView(const GltfCamera& camera);

// Looks at the box [lo, hi] from the front (+Z) and a little above (+Y), far enough back that its bounding
// sphere fits the view at the given image aspect (width / height).
CameraView frameBounds(const glm::vec3& lo, const glm::vec3& hi, float aspect);

// A committed "perspective" or "orthographic" camera showing `view` at the given image aspect.
ANARICamera newAnariCamera(ANARIDevice device, const CameraView& view, float aspect);

// Sets and commits `view` on a camera of its kind (perspective or orthographic) made by newAnariCamera.
void setAnariCamera(ANARIDevice device, ANARICamera camera, const CameraView& view, float aspect);

}  // namespace ripple::apps
