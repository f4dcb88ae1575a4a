// The viewer's scene panels: Lights (each light's colour, intensity and direction, the environment's
// intensity and turn) and Volumes (each volume's colour map, opacity curve, value range and unit distance,
// each iso-surface's value). They edit a SceneEdits' records in place and say which changed; the caller
// commits those between passes (ProgressiveFrames::editScene).
#pragma once

#include "apps/scene/SceneEdits.h"

namespace ripple::apps {

// Draws the panels of what `edits` lists (none for an empty list).
SceneEditRequests drawScenePanels(SceneEdits& edits);

}  // namespace ripple::apps
