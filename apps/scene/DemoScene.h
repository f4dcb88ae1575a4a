// Built-in scenes made through ANARI with no files: "default" (spheres, a torus and pillars of several
// materials on a tiled floor, sun and area light), "cornell" (the Cornell box built procedurally) and
// "volume" (a Marschner-Lobb field as a scattering medium on a floor) and "isosurface" (the same field's
// surface at 0.5, in gold); and the same stage for a field read from a file (buildFieldScene).
#pragma once

#include "apps/scene/AnariScene.h"
#include "io/volume/VolumeFile.h"
#include "io/volume/NanoVdbFile.h"
#include "io/vtk/VtkAmrFile.h"
#include "io/vtk/VtkUnstructuredFile.h"

#include <optional>
#include <string>
#include <vector>

namespace ripple::apps {

// The names buildDemoScene accepts.
std::vector<std::string> demoSceneNames();

// Throws std::invalid_argument listing the known names when `name` is not one of them.
void checkDemoSceneName(const std::string& name);

// Builds the named demo scene on `device`; the world's cameras hold its one good view. extraLights (an
// environment, say; the caller keeps them) join the scene's own. Throws as checkDemoSceneName does for an
// unknown name. edits: where given, the scene's lights, volumes and iso-surfaces are listed there.
AnariWorld buildDemoScene(ANARIDevice device, const std::string& name, const std::vector<ANARILight>& extraLights = {},
                          SceneEdits* edits = nullptr);

// The colour maps buildFieldScene takes: viridis, coolwarm, grayscale.
std::vector<std::string> transferFunctionNames();

// Throws std::invalid_argument listing the known names when `name` is not one of them.
void checkTransferFunctionName(const std::string& name);

// The named colour map's control points, evenly spaced (as a transferFunction1D's color array); throws as
// checkTransferFunctionName does.
std::vector<glm::vec3> transferFunctionColors(const std::string& name);

// What buildFieldScene draws of a field.
struct FieldSceneOptions {
    // Colour map of the volume; empty: no volume (then isovalues should not be empty). The colours spread
    // over the data's value range, min..max of the voxels, with opacity rising linearly from 0 at min to
    // `opacity` at max.
    std::string transferFunction = "viridis";
    float opacity = 0.5f;
    // World units in which `opacity` holds (the field's longest side is 2); 0.2 when not given.
    std::optional<float> unitDistance;
    // One isosurface geometry per value, coloured by the colour map at the value (viridis when there is
    // no volume).
    std::vector<float> isovalues;
    // The values the colour map spans; default: the data's min..max (under mpirun: every rank's).
    std::optional<glm::vec2> valueRange;
    // The floor and the sun (under mpirun only rank 0's world holds them; every rank's field is placed
    // in the whole field's box, and every camera frames it).
    bool stage = true;
};

constexpr float kDefaultUnitDistance = 0.2f;

// The field of `data` on the demos' floor under their sun and sky, scaled so that its longest side is 2
// and centred over the origin, standing just above the floor (the file's y axis points up); a camera
// frames it. A slab (data.zFirst, data.wholeDims) takes its place in the whole field's box. Throws as
// checkTransferFunctionName does.
AnariWorld buildFieldScene(ANARIDevice device, const VolumeData& data, const FieldSceneOptions& options,
                           const std::vector<ANARILight>& extraLights = {}, SceneEdits* edits = nullptr);

// One rank's part of an unstructured mesh (the whole mesh on one rank), with the whole mesh's box.
struct MeshPart {
    UnstructuredMesh cells;              // minValue, maxValue: the whole mesh's
    glm::vec3 wholeLo{0.0f}, wholeHi{0.0f};
};

// The mesh on the same stage as buildFieldScene's field, placed the same way (its whole box's longest side
// 2, centred, just above the floor), as an unstructured field drawn as a volume and iso-surfaces as
// `options` say.
AnariWorld buildMeshScene(ANARIDevice device, const MeshPart& mesh, const FieldSceneOptions& options,
                          const std::vector<ANARILight>& extraLights = {}, SceneEdits* edits = nullptr);

// A NanoVDB grid on the same stage, placed the same way (its world box's longest side 2, centred, just
// above the floor, by an instance transform), drawn as a volume. Iso-surfaces of NanoVDB fields are not
// drawn: the device refuses them by name.
AnariWorld buildNanoVdbScene(ANARIDevice device, const NanoVdbFile& grid, const FieldSceneOptions& options,
                             const std::vector<ANARILight>& extraLights = {}, SceneEdits* edits = nullptr);

// One rank's part of an AMR hierarchy (the whole on one rank: AmrPartition.h), with the whole's object-space box.
struct AmrPart {
    AmrData blocks;                      // minValue, maxValue: the whole hierarchy's
    glm::dvec3 wholeLo{0.0}, wholeHi{0.0};
};

// An AMR hierarchy on the same stage, placed the same way (the whole's box's longest side 2, centred, just
// above the floor, by an instance transform), drawn as a volume of the finest covering cell's values.
// Iso-surfaces of AMR fields are not drawn: the device refuses them by name.
AnariWorld buildAmrScene(ANARIDevice device, const AmrPart& amr, const FieldSceneOptions& options,
                         const std::vector<ANARILight>& extraLights = {}, SceneEdits* edits = nullptr);

}  // namespace ripple::apps
