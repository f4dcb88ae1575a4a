// The parts of a built scene that a viewer edits afterwards: lights (colour, intensity, a directional or spot
// light's direction, an environment's intensity and turn), volumes' transfer functions (colour map, opacity
// curve, value range, unit distance) and iso-surfaces' values. The scene builders fill a SceneEdits when
// given one; it retains the handles it lists (and releases them when destroyed), and commit() sets an edited
// record's values on its object.
#pragma once

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ripple::apps {

struct EditableLight {
    ANARILight handle = nullptr;
    std::string label;                  // what the panel calls it: "sun", a glTF light's name, "environment"
    std::string subtype;                // directional, point, spot, quad, hdri
    glm::vec3 color{1.0f};
    float intensity = 1.0f;             // the subtype's own: see intensityParameter
    std::optional<glm::vec3> direction; // directional and spot: where the light shines
    float rotationDegrees = 0.0f;       // hdri: its turn about +Y (environmentDirection)
};

struct EditableVolume {
    ANARIVolume handle = nullptr;
    std::string label;
    std::vector<glm::vec3> colors;      // the transferFunction1D's color array, evenly over valueRange
    std::vector<float> opacities;       // its opacity array, likewise
    glm::vec2 valueRange{0.0f, 1.0f};
    float unitDistance = 1.0f;
    glm::vec2 dataRange{0.0f, 1.0f};    // the field's smallest and largest sample (the panel's slider range)
    std::vector<glm::vec3> sceneColors; // the colours as built (SceneEdits::add copies them)
    std::string colorMap;               // the named map `colors` holds (transferFunctionColors); empty: the scene's
};

struct EditableIsosurface {
    ANARIGeometry handle = nullptr;
    std::string label;
    float isovalue = 0.0f;
    glm::vec2 dataRange{0.0f, 1.0f};
};

// The parameter holding a light subtype's intensity: irradiance (directional), radiance (quad, ring),
// scale (hdri), intensity (point, spot).
const char* intensityParameter(const std::string& lightSubtype);

// Which records of a SceneEdits changed (indices into its lists), to be committed together.
struct SceneEditRequests {
    std::set<size_t> lights, volumes, isosurfaces;
    bool empty() const { return lights.empty() && volumes.empty() && isosurfaces.empty(); }
    void merge(const SceneEditRequests& other) {
        lights.insert(other.lights.begin(), other.lights.end());
        volumes.insert(other.volumes.begin(), other.volumes.end());
        isosurfaces.insert(other.isosurfaces.begin(), other.isosurfaces.end());
    }
};

class SceneEdits {
public:
    explicit SceneEdits(ANARIDevice device) : device_(device) {}
    ~SceneEdits();
    SceneEdits(const SceneEdits&) = delete;
    SceneEdits& operator=(const SceneEdits&) = delete;

    // Each retains the record's handle.
    void add(EditableLight light);
    void add(EditableVolume volume);
    void add(EditableIsosurface isosurface);

    // Sets the record's values on its object and commits it (the frame restarts its accumulation).
    void commit(const EditableLight& light) const;
    void commit(const EditableVolume& volume) const;
    void commit(const EditableIsosurface& isosurface) const;
    // Commits the requested records.
    void commit(const SceneEditRequests& requests) const;

    std::vector<EditableLight> lights;  // edited in place, then committed
    std::vector<EditableVolume> volumes;
    std::vector<EditableIsosurface> isosurfaces;

private:
    ANARIDevice device_;
};

}  // namespace ripple::apps
