// Dear ImGui panels of the viewer (see ViewerPanels.h).
#include "apps/ripple-view/ViewerPanels.h"

#include <imgui.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace ripple::apps {
namespace {

void rendererPanel(ViewerUiState& ui, PanelRequests& out) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Renderer")) {
        ViewerSettings& s = ui.settings;
        out.settingsChanged |= ImGui::SliderInt("samples per pass", &s.pixelSamples, 1, 64);
        out.settingsChanged |= ImGui::SliderInt("max path length", &s.maxPathLength, 1, 32);
        out.settingsChanged |= ImGui::ColorEdit3("background", &s.background.x, ImGuiColorEditFlags_Float);
        out.settingsChanged |= ImGui::SliderFloat("ambient radiance", &s.ambientRadiance, 0.0f, 4.0f);
        int maxSamples = int(ui.maxSamples);
        if (ImGui::InputInt("stop at spp (0: never)", &maxSamples, 64)) ui.maxSamples = uint32_t(std::max(maxSamples, 0));
        ImGui::Checkbox("reduce while moving", &ui.reduceWhileMoving);
        const DisplayChannelInfo& shown = displayChannelInfo(s.display);
        if (ImGui::BeginCombo("show", shown.label)) {
            for (const DisplayChannelInfo& c : displayChannels())
                if ((!ui.onlyGatheredChannels || c.channel == DisplayChannel::Color || c.channel == DisplayChannel::Depth) &&
                    ImGui::Selectable(c.label, c.channel == s.display)) {
                    s.display = c.channel;
                    out.settingsChanged = true;
                }
            ImGui::EndCombo();
        }
        if (!ui.traversals.empty() &&
            ImGui::BeginCombo("traversal", ui.traversal.empty() ? "the device's default" : ui.traversal.c_str())) {
            for (const std::string& t : ui.traversals)
                if (ImGui::Selectable(t.c_str(), t == ui.traversal)) {
                    ui.traversal = t;
                    out.traversalChanged = true;
                }
            ImGui::EndCombo();
        }
        if (ui.quickLookAvailable)
            out.settingsChanged |= ImGui::Checkbox("quick look while moving (eyeLight)", &s.quickLookWhileMoving);
        if (ui.reduceWhileMoving) ImGui::SliderInt("size divisor", &ui.movingDivisor, 2, 8);
        out.screenshot |= ImGui::Button("screenshot (P)");
        ImGui::SameLine();
        out.screenshotExr |= ImGui::Button("EXR (shift+P)");
        ImGui::SameLine();
        out.saveView |= ImGui::Button("save view (V)");
    }
    ImGui::End();
}

void cameraPanel(ViewerUiState& ui, CameraView& view, const std::vector<CameraView>& cameras, PanelRequests& out) {
    ImGui::SetNextWindowPos(ImVec2(10, 40), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Camera")) {
        const auto label = [&](int i) {
            if (i < 0) return std::string("framed on the scene (F)");
            const std::string& name = cameras[size_t(i)].name;
            return "camera " + std::to_string(i) + (name.empty() ? "" : ": " + name);
        };
        if (ImGui::BeginCombo("view", label(ui.selectedCamera).c_str())) {
            for (int i = -1; i < int(cameras.size()); ++i)
                if (ImGui::Selectable(label(i).c_str(), i == ui.selectedCamera)) {
                    ui.selectedCamera = i;
                    if (i < 0) out.frameScene = true;
                    else {
                        view = cameras[size_t(i)];
                        out.viewChanged = true;
                    }
                }
            ImGui::EndCombo();
        }
        if (view.orthographic) {
            out.viewChanged |= ImGui::SliderFloat("view height", &view.height, 1e-3f, 1e3f, "%.3f",
                                                  ImGuiSliderFlags_Logarithmic);
        } else {
            float degrees = glm::degrees(view.fovy);
            if (ImGui::SliderFloat("field of view", &degrees, 5.0f, 150.0f, "%.1f deg")) {
                view.fovy = glm::radians(degrees);
                out.viewChanged = true;
            }
            // Depth of field: 0 is a pinhole.
            out.viewChanged |= ImGui::SliderFloat("aperture radius", &view.apertureRadius, 0.0f, 1.0f, "%.4f",
                                                  ImGuiSliderFlags_Logarithmic);
            out.viewChanged |= ImGui::SliderFloat("focus distance", &view.focusDistance, 1e-3f, 1e3f, "%.3f",
                                                  ImGuiSliderFlags_Logarithmic);
            view.apertureRadius = std::max(view.apertureRadius, 0.0f);
            view.focusDistance = std::max(view.focusDistance, 1e-3f);
        }
        ImGui::Text("position  %.3f %.3f %.3f", view.position.x, view.position.y, view.position.z);
        ImGui::Text("direction %.3f %.3f %.3f", view.direction.x, view.direction.y, view.direction.z);
        ImGui::TextUnformatted("left drag: orbit, right/middle drag: pan,\nwheel: zoom, WASD/QE: fly (shift: faster),\n"
                               "F: frame the scene, P: screenshot, V: save the view");
    }
    ImGui::End();
}

void statsOverlay(const PassResult& pass, uint32_t fullSamples, bool moving, bool busy) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 10, display.y - 10), ImGuiCond_Always, ImVec2(1, 1));
    ImGui::SetNextWindowBgAlpha(0.5f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoInputs;  // mouse drags pass through to the camera
    if (ImGui::Begin("stats", nullptr, flags)) {
        ImGui::Text("%u spp%s", moving ? pass.samples : fullSamples, busy ? "" : " (idle)");
        ImGui::Text("%.1f ms per pass, %ux%u%s", pass.milliseconds, pass.size.x, pass.size.y,
                    pass.reduced ? " (moving)" : "");
        if (pass.raysPerSecond) ImGui::Text("%.2f Mrays/s", double(*pass.raysPerSecond) * 1e-6);
        if (!std::isnan(pass.estimate.relMse))
            ImGui::Text("estimated relMSE %.2e (%.1e .. %.1e)", pass.estimate.relMse, pass.estimate.low,
                        pass.estimate.high);
    }
    ImGui::End();
}

}  // namespace

PanelRequests drawPanels(ViewerUiState& ui, CameraView& view, const std::vector<CameraView>& cameras,
                         const PassResult& pass, uint32_t fullSamples, bool moving, bool busy) {
    PanelRequests out;
    rendererPanel(ui, out);
    cameraPanel(ui, view, cameras, out);
    statsOverlay(pass, fullSamples, moving, busy);
    return out;
}

}  // namespace ripple::apps
