// The viewer's scene panels: Lights (each light's colour, intensity and direction, the environment's
// intensity and turn) and Volumes (each volume's colour map, opacity curve, value range and unit distance,
// each iso-surface's value). They edit a SceneEdits' records in place and say which changed; the caller
// commits those between passes (ProgressiveFrames::editScene).
#pragma once

#include "apps/common/SceneEdits.h"

#include <cstddef>
#include <set>

namespace ripple::apps {

struct SceneEditRequests {
    std::set<size_t> lights, volumes, isosurfaces;  // indices into SceneEdits' lists
    bool empty() const { return lights.empty() && volumes.empty() && isosurfaces.empty(); }
    void merge(const SceneEditRequests& other) {
        lights.insert(other.lights.begin(), other.lights.end());
        volumes.insert(other.volumes.begin(), other.volumes.end());
        isosurfaces.insert(other.isosurfaces.begin(), other.isosurfaces.end());
    }
};

// Draws the panels of what `edits` lists (none for an empty list).
SceneEditRequests drawScenePanels(SceneEdits& edits);

// Commits the requested records.
void commitEdits(const SceneEdits& edits, const SceneEditRequests& requests);

}  // namespace ripple::apps
