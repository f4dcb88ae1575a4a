// ripple-render's command line: the options with their flags and help, what every rank must agree on under
// mpirun, and a view file's settings applied beneath the command line's.
#pragma once

#include "apps/ripple-render/RankAgreement.h"
#include "apps/scene/EnvironmentOptions.h"
#include "apps/scene/ViewState.h"
#include "apps/scene/VolumeOptions.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ripple::apps {

struct Options {
    std::string scene;                  // a .gltf/.glb, or empty for a demo scene
    std::string demo;
    std::string output = "ripple.png";
    std::string size = "512x512";
    uint32_t spp = 16;
    std::string library = "ripple";
    std::string renderer = "default";   // the ANARI renderer subtype
    std::string traversal;              // the device parameter "traversal"; empty: the device's default
    std::string exchange;               // the device parameter "rayExchange"; empty: the device's default
    uint32_t maxPathLength = 5;
    uint32_t seed = 0;                  // the renderer's "seed": a reference must not share the image's samples
    std::optional<int> camera;
    std::optional<float> ambient;
    std::string view;                   // a view-state file (ripple-view's): camera, renderer settings, size
    std::vector<std::string> channels;  // --channels: depth, normal, albedo as layers of the EXR output
    bool exrHalf = false;               // the EXR output's colour, normal and albedo as half floats
    std::optional<ViewState> viewState; // --view's contents (its ambient counts unless --ambient is given)
    EnvironmentOptions environment;     // --environment: an hdri light
    bool quiet = false;
    std::string partition = "round-robin";  // under mpirun: which share of the file each rank imports
    std::filesystem::path resourceRoot;     // empty: the scene file's folder confines its URIs
    bool stats = false;
    bool listDevices = false;           // list the Vulkan devices the ANARI device sees, then exit
    std::string reference;              // converged image of the same view: the true error is reported too
    std::string report;                 // CSV of the convergence series; its plot goes beside it as .png
    std::string errorMap;               // each pixel's estimated relMSE: PFM/EXR values or a PNG heat map
    std::optional<double> seconds;      // --time: the whole run, start-up included, ends within this
    std::optional<double> targetError;  // stop when the estimated relMSE reaches this
    bool sppGiven = false;              // --spp on the command line: it caps --time and --target-error too
    VolumeOptions field;                // --volume: a scalar field drawn as a volume and/or isosurfaces

    // Reporting mode: one sample per frame, so that the series has points, and a line per report point.
    bool reporting() const { return !reference.empty() || !report.empty() || seconds || targetError; }
};

// The estimate is too unsteady to stop on before this many samples (each half needs a few batches).
constexpr uint32_t kMinSamplesForTarget = 8;
constexpr uint32_t kMaxSpp = 1000000;

// Every option of ripple-render, bound to `options`.
void addRenderOptions(CLI::App& app, Options& options);

// Under mpirun: the options every rank must share, and whether its command line parsed (exit code + 1, 0
// when it did), so that ranks whose command lines differ all stop with one message.
std::vector<AgreedOption> agreedOptions(const Options& options, int parseOutcome);

// --view: the file's camera replaces the scene's, and its renderer settings and size apply where the command
// line does not set them (the file's pixelSamples is the viewer's pass size: --spp counts here).
void applyViewState(Options& options, const CLI::App& app);

}  // namespace ripple::apps
