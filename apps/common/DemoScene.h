// Built-in scenes made through ANARI with no files: "default" (spheres, a torus and pillars of several
// materials on a tiled floor, sun and area light), "cornell" (the Cornell box built procedurally) and
// "volume" (a Marschner-Lobb field as a scattering medium on a floor) and "isosurface" (the same field's
// surface at 0.5, in gold).
#pragma once

#include "apps/common/AnariScene.h"

#include <string>
#include <vector>

namespace ripple::apps {

// The names buildDemoScene accepts.
std::vector<std::string> demoSceneNames();

// Throws std::invalid_argument listing the known names when `name` is not one of them.
void checkDemoSceneName(const std::string& name);

// Builds the named demo scene on `device`; the world's cameras hold its one good view. extraLights (an
// environment, say; the caller keeps them) join the scene's own. Throws as checkDemoSceneName does for an
// unknown name.
AnariWorld buildDemoScene(ANARIDevice device, const std::string& name, const std::vector<ANARILight>& extraLights = {});

}  // namespace ripple::apps
