// The lights the shading kernels sample: the description's lights, plus one LIGHT_TRIANGLE record per
// triangle of every instance whose material is emissive without an emission texture (world space, so
// they can be gathered from many ranks like any other light), the importance-sampling tables of an hdri
// light, and each light's chance of being picked for next-event estimation (proportional to its power).
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/material.h"

#include <string>
#include <vector>

namespace ripple::core {

struct ShadingTables;

// Emissive triangles beyond this many are not made lights (their materials lose MATERIAL_FLAG_LIGHT, so
// they are found by BSDF-sampled rays only), which bounds the light table.
inline constexpr uint64_t kMaxTriangleLights = 1u << 20;

// Power a light is picked in proportion to: its flux (W, luminance-weighted). Directional and hdri lights
// count the flux through the scene's bounding sphere of radius sceneRadius.
double lightSelectionPower(const gpu::LightRecord& light, float sceneRadius, float environmentLuminance);

// The chance that next-event estimation samples the ambient light (uniform radiance `ambient`) rather than
// one of the scene's lights, whose selection powers add up to lightPowerTotal: in proportion to its power,
// counted as the irradiance it gives a surface open to the whole sky (pi times its luminance) through the
// scene's disc, as a directional light of that irradiance would be. 0 without ambient light; 1 without lights,
// and only then.
float ambientLightChance(const glm::vec3& ambient, float sceneRadius, float lightPowerTotal);

// Fills out.lights, out.lightPowerTotal, out.testedLightCount and out.environmentLight; appends hdri
// tables to out.texels. Needs out.materials and out.textures already built.
void buildLightTable(const SceneDescription& description, float sceneRadius, ShadingTables& out);

}  // namespace ripple::core
