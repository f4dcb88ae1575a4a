// Dear ImGui panels of the scene's lights and volumes (see ScenePanels.h).
#include "apps/ripple-view/ScenePanels.h"

#include "apps/scene/DemoScene.h"

#include <imgui.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace ripple::apps {
namespace {

// Where a light shines as two angles, degrees: azimuth about +Y from +Z, elevation above the horizon.
glm::vec2 anglesOf(const glm::vec3& direction) {
    const glm::vec3 d = glm::normalize(direction);
    return {glm::degrees(std::atan2(d.x, d.z)), glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)))};
}

glm::vec3 directionOf(const glm::vec2& degrees) {
    const float azimuth = glm::radians(degrees.x), elevation = glm::radians(degrees.y);
    return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
}

bool lightControls(EditableLight& light) {
    bool changed = false;
    if (light.subtype != "hdri") changed |= ImGui::ColorEdit3("colour", &light.color.x, ImGuiColorEditFlags_Float);
    const std::string name = std::string(intensityParameter(light.subtype));
    changed |= ImGui::DragFloat(name.c_str(), &light.intensity, 0.01f * std::max(light.intensity, 0.1f), 0.0f, 1e6f,
                                "%.3f");
    light.intensity = std::max(light.intensity, 0.0f);
    if (light.direction) {
        glm::vec2 angles = anglesOf(*light.direction);
        bool turned = ImGui::SliderFloat("azimuth", &angles.x, -180.0f, 180.0f, "%.1f deg");
        turned |= ImGui::SliderFloat("elevation", &angles.y, -90.0f, 90.0f, "%.1f deg");
        if (turned) {
            light.direction = directionOf(angles);
            changed = true;
        }
    }
    if (light.subtype == "hdri")
        changed |= ImGui::SliderFloat("rotation", &light.rotationDegrees, -180.0f, 180.0f, "%.1f deg");
    return changed;
}

bool volumeControls(EditableVolume& volume) {
    bool changed = false;
    const std::string shown = volume.colorMap.empty() ? "the scene's" : volume.colorMap;
    if (ImGui::BeginCombo("colour map", shown.c_str())) {
        if (ImGui::Selectable("the scene's", volume.colorMap.empty())) {
            volume.colorMap.clear();
            volume.colors = volume.sceneColors;
            changed = true;
        }
        for (const std::string& name : transferFunctionNames())
            if (ImGui::Selectable(name.c_str(), name == volume.colorMap)) {
                volume.colorMap = name;
                volume.colors = transferFunctionColors(name);
                changed = true;
            }
        ImGui::EndCombo();
    }
    // The opacity curve: one vertical slider per array entry, evenly over the value range.
    std::vector<float>& o = volume.opacities;
    ImGui::PlotLines("##opacity curve", o.data(), int(o.size()), 0, "opacity", 0.0f, 1.0f, ImVec2(0, 50));
    if (o.size() <= 64) {
        for (size_t i = 0; i < o.size(); ++i) {
            ImGui::PushID(int(i));
            if (i > 0) ImGui::SameLine(0.0f, 1.0f);
            changed |= ImGui::VSliderFloat("##o", ImVec2(10, 70), &o[i], 0.0f, 1.0f, "");
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("entry %zu: %.3f", i, double(o[i]));
            ImGui::PopID();
        }
    }
    if (ImGui::Button("ramp")) {  // 0 at the low end to the largest entry at the high end
        const float top = o.empty() ? 1.0f : std::max(*std::max_element(o.begin(), o.end()), 0.05f);
        for (size_t i = 0; i < o.size(); ++i) o[i] = o.size() > 1 ? top * float(i) / float(o.size() - 1) : top;
        changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("clear")) {
        std::fill(o.begin(), o.end(), 0.0f);
        changed = true;
    }
    const float span = std::max(volume.dataRange.y - volume.dataRange.x, 1e-6f);
    changed |= ImGui::DragFloatRange2("value range", &volume.valueRange.x, &volume.valueRange.y, 0.002f * span,
                                      volume.dataRange.x - span, volume.dataRange.y + span, "%.4g");
    if (!(volume.valueRange.y > volume.valueRange.x)) volume.valueRange.y = volume.valueRange.x + 1e-3f * span;
    changed |= ImGui::SliderFloat("unit distance", &volume.unitDistance, 1e-4f, 100.0f, "%.4g",
                                  ImGuiSliderFlags_Logarithmic);
    volume.unitDistance = std::max(volume.unitDistance, 1e-6f);
    return changed;
}

}  // namespace

SceneEditRequests drawScenePanels(SceneEdits& edits) {
    SceneEditRequests out;
    if (!edits.lights.empty()) {
        ImGui::SetNextWindowPos(ImVec2(10, 70), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
        if (ImGui::Begin("Lights")) {
            for (size_t i = 0; i < edits.lights.size(); ++i) {
                EditableLight& light = edits.lights[i];
                ImGui::PushID(int(i));
                if (ImGui::TreeNode("light", "%s (%s)", light.label.c_str(), light.subtype.c_str())) {
                    if (lightControls(light)) out.lights.insert(i);
                    ImGui::TreePop();
                }
                ImGui::PopID();
            }
        }
        ImGui::End();
    }
    if (!edits.volumes.empty() || !edits.isosurfaces.empty()) {
        ImGui::SetNextWindowPos(ImVec2(10, 100), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
        if (ImGui::Begin("Volumes")) {
            for (size_t i = 0; i < edits.volumes.size(); ++i) {
                ImGui::PushID(int(i));
                if (ImGui::TreeNodeEx("volume", ImGuiTreeNodeFlags_DefaultOpen, "%s", edits.volumes[i].label.c_str())) {
                    if (volumeControls(edits.volumes[i])) out.volumes.insert(i);
                    ImGui::TreePop();
                }
                ImGui::PopID();
            }
            for (size_t i = 0; i < edits.isosurfaces.size(); ++i) {
                EditableIsosurface& iso = edits.isosurfaces[i];
                ImGui::PushID(int(1000 + i));
                if (ImGui::SliderFloat(iso.label.c_str(), &iso.isovalue, iso.dataRange.x, iso.dataRange.y, "%.4g"))
                    out.isosurfaces.insert(i);
                ImGui::PopID();
            }
        }
        ImGui::End();
    }
    return out;
}

}  // namespace ripple::apps
