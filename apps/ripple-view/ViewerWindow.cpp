// GLFW window, OpenGL 3.3 context and Dear ImGui set-up of the viewer (see ViewerWindow.h).
#include "apps/ripple-view/ViewerWindow.h"

#include "apps/ripple-view/ProgressiveFrames.h"
#include "io/image/ImageIO.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>  // OpenGL 1.1's texture calls, which libGL exports; ImGui loads the rest itself
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace ripple::apps {
namespace {

std::string lastGlfwError;

void onGlfwError(int, const char* description) { lastGlfwError = description ? description : "unknown GLFW error"; }

std::string noDisplayAdvice() {
    return "; ripple-view needs a display: render without one with ripple-render (same scenes and options), or "
           "run the viewer under a virtual X server: xvfb-run -a ripple-view ...";
}

}  // namespace

ViewerWindow::ViewerWindow(glm::uvec2 size, const std::string& title) {
    glfwSetErrorCallback(onGlfwError);
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        throw NoDisplay("cannot open a window: no display (DISPLAY is not set)" + noDisplayAdvice());
    if (!glfwInit()) throw NoDisplay("cannot open a window: " + lastGlfwError + noDisplayAdvice());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(int(size.x), int(size.y), title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw NoDisplay("cannot open an OpenGL 3.3 window: " + lastGlfwError + noDisplayAdvice());
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

ViewerWindow::~ViewerWindow() {
    glDeleteTextures(1, &texture_);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool ViewerWindow::closing() const { return glfwWindowShouldClose(window_); }
void ViewerWindow::close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void ViewerWindow::beginFrame(double seconds) {
    // Waiting, not spinning: on a CPU device the render competes with this thread for the cores.
    glfwWaitEventsTimeout(seconds);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ViewerWindow::showImage(const PassResult& pass) {
    const std::vector<float>& shown = pass.display.empty() ? pass.rgba : pass.display;
    const std::vector<uint8_t> bytes = encodeSrgb8(pass.size.x, pass.size.y, shown.data());
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, GLsizei(pass.size.x), GLsizei(pass.size.y), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 bytes.data());
    hasImage_ = true;
}

void ViewerWindow::endFrame() {
    const glm::uvec2 size = framebufferSize();
    if (hasImage_) {
        // The frame's row 0 is its bottom row: flip the texture coordinates.
        const ImVec2 window = ImGui::GetIO().DisplaySize;
        ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(uintptr_t(texture_)), ImVec2(0, 0), window,
                                                 ImVec2(0, 1), ImVec2(1, 0));
    }
    ImGui::Render();
    glViewport(0, 0, GLsizei(size.x), GLsizei(size.y));
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window_);
}

glm::uvec2 ViewerWindow::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}

}  // namespace ripple::apps
