// Materials, textures and lights of a SceneDescription, validated and converted to the records of
// shaders/shared/material.h. Bad values never reach a kernel: they are replaced or skipped and named.
#pragma once

#include "core/scene/SceneDescription.h"
#include "shaders/shared/material.h"

#include <string>
#include <vector>

namespace ripple::core {

struct ShadingTables {
    // The input materials in order, then one default matte that instances with a bad index use.
    std::vector<gpu::MaterialRecord> materials;
    std::vector<gpu::TextureRecord> textures;  // one per input texture (a bad one keeps its slot, unused)
    std::vector<uint32_t> texels;              // every texture's words, at TextureRecord::texelOffset
    std::vector<gpu::LightRecord> lights;      // valid lights, then emissive triangles (core/scene/LightTable.h)
    float lightPowerTotal = 0.0f;              // sum of the lights' selection powers
    uint32_t testedLightCount = 0;             // lights[0, this) are the ones rays test (quad, ring, hdri, disc sun)
    int32_t environmentLight = -1;             // index in lights of the hdri light, or -1
    uint32_t bsdfTableOffset = 0;              // first word of the BSDF energy tables in texels
    uint64_t triangleLights = 0;               // LIGHT_TRIANGLE records made from emissive geometry
    std::vector<gpu::LightRecord> localTriangleLights;  // those records (not the description's foreign ones)
    uint64_t materialsRepaired = 0;            // materials with a value replaced by its default
    uint64_t texturesSkipped = 0;              // wrong size or format: materials sample them as absent
    uint64_t texelsRepaired = 0;               // non-finite float texels replaced by 0
    uint64_t lightsSkipped = 0;
    std::vector<std::string> messages;
};

// sceneRadius: of the scene's bounding sphere (the flux of directional and hdri lights is counted through it).
ShadingTables buildShadingTables(const SceneDescription& description, float sceneRadius = 1.0f);

// Index of the default material in ShadingTables::materials.
inline uint32_t defaultMaterialIndex(const SceneDescription& description) {
    return static_cast<uint32_t>(description.materials.size());
}

}  // namespace ripple::core
