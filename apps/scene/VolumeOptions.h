// The command-line options that draw a volume file, shared by ripple-render and ripple-view: the file, a
// raw file's layout, the colour map, opacity, unit distance and isovalues; and the file read and checked
// into what buildFieldScene draws (under mpirun each rank reads only its z-slab), or an unstructured grid
// into what buildMeshScene draws (under mpirun each rank keeps only its part of the cells).
#pragma once

#include "apps/scene/DemoScene.h"
#include "io/volume/VolumeFile.h"
#include "mpi/Communicator.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace ripple::apps {

struct VolumeOptions {
    std::string volume;                 // --volume: a raw or NRRD file; empty: none
    std::string dims, type, spacing;    // raw files only
    std::string field;                  // --field: a VTK file's point array; empty: its active scalars
    std::optional<int> fieldComponent;  // --field-component: one of a vector's components (else its magnitude)
    bool listFields = false;            // --list-fields: print the file's arrays and stop
    std::string transferFunction;       // --tf; empty: viridis, unless --isovalue is given (then no volume)
    std::optional<float> opacity, unitDistance;
    std::vector<float> isovalues;
};

// Adds --volume, --dims, --type, --spacing, --tf, --opacity, --unit-distance and --isovalue to `app`.
void addVolumeOptions(CLI::App& app, VolumeOptions& options);

// --list-fields: the arrays of options.volume, one a line, on stdout. Throws VolumeError.
void printVolumeFields(const VolumeOptions& options);

// The volume options as one string: equal on ranks given the same options (ripple-render checks that).
std::string describeVolumeOptions(const VolumeOptions& options);

struct FieldPlan {
    VolumeData data;                    // this rank's slab; minValue/maxValue span every rank's
    std::optional<MeshPart> mesh;       // an unstructured grid instead: this rank's part of it
    std::optional<NanoVdbFile> nanovdb; // a NanoVDB grid instead (one rank only)
    std::optional<AmrPart> amr;         // an AMR hierarchy instead: this rank's part of it
    FieldSceneOptions scene;
};

// Checks what can be checked without reading the file: options that need --volume, the colour map's name,
// finite isovalues. Throws naming the option.
void checkVolumeOptions(const VolumeOptions& options);

// Reads and checks --volume's file with what to draw of it; nothing when no --volume is given. Throws naming
// the option or the file (also for the other volume options without --volume). Collective under mpirun.
// `root` places the floor and the sun in this rank's world; it also prints the warnings (`program` names
// them) unless `quiet`.
std::optional<FieldPlan> planField(const VolumeOptions& options, const mpi::Communicator& ranks, bool root,
                                   const char* program, bool quiet);

// The planned field's scene: buildFieldScene, or buildMeshScene for a mesh.
AnariWorld buildPlannedField(ANARIDevice device, const FieldPlan& plan, const std::vector<ANARILight>& extraLights,
                             SceneEdits* edits);

}  // namespace ripple::apps
