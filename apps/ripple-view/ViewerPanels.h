// The viewer's Dear ImGui panels: renderer settings, camera, and the statistics overlay. They edit plain
// values; the caller turns changes into ANARI commits.
#pragma once

#include "apps/ripple-view/ProgressiveFrames.h"
#include "apps/scene/AnariScene.h"

#include <string>
#include <vector>

namespace ripple::apps {

struct ViewerUiState {
    ViewerSettings settings;
    uint32_t maxSamples = 4096;         // the full frame stops accumulating here (0: never)
    bool reduceWhileMoving = true;      // render at reduced size while the view moves
    int movingDivisor = 2;              // each side divided by this while it moves
    int selectedCamera = -1;            // index into the scene's cameras; -1: framed on the bounds
    bool quickLookAvailable = false;    // the device has the "eyeLight" renderer (the panel offers it)
    bool onlyGatheredChannels = false;  // under mpirun: only colour and depth reach rank 0 (the panel offers those)
    // The device parameter 'traversal''s values where the device lists them (Ripple: auto, software,
    // rayQuery), and the one chosen (empty: the device's default).
    std::vector<std::string> traversals;
    std::string traversal;
};

// What the user asked for in the panels this frame.
struct PanelRequests {
    bool settingsChanged = false;
    bool viewChanged = false;           // the field of view, or a camera chosen
    bool frameScene = false;
    bool screenshot = false;            // PNG
    bool screenshotExr = false;         // EXR (linear, unclipped)
    bool saveView = false;              // write the view-state file (as the V key does)
    bool traversalChanged = false;      // ui.traversal: set it on the device
};

// Draws the panels; `view` and `ui` are edited in place.
PanelRequests drawPanels(ViewerUiState& ui, CameraView& view, const std::vector<CameraView>& cameras,
                         const PassResult& pass, uint32_t fullSamples, bool moving, bool busy);

}  // namespace ripple::apps
