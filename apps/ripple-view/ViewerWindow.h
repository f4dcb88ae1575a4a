// The viewer's window: GLFW with an OpenGL 3.3 core context (Mesa's llvmpipe is enough, so it runs on any X
// server and under Xvfb), Dear ImGui on its GLFW and OpenGL 3 back-ends, and the last pass's image as a
// texture stretched over the window behind the panels.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace ripple::apps {

struct PassResult;

// No window could be opened: no display, or no OpenGL 3.3 on it. The message says what to do instead.
struct NoDisplay : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class ViewerWindow {
public:
    // Opens a window whose drawable is `size` pixels where the window system allows. Throws NoDisplay.
    ViewerWindow(glm::uvec2 size, const std::string& title);
    ~ViewerWindow();
    ViewerWindow(const ViewerWindow&) = delete;
    ViewerWindow& operator=(const ViewerWindow&) = delete;

    bool closing() const;
    void close();
    // Handles the window system's events, waiting at most `seconds` for one, and starts an ImGui frame.
    void beginFrame(double seconds);
    // Uploads the pass's linear pixels (its picture of another channel, where it has one), sRGB-encoded, as
    // the image shown from now on.
    void showImage(const PassResult& pass);
    // Draws the image and the panels and presents them.
    void endFrame();
    glm::uvec2 framebufferSize() const;
    GLFWwindow* handle() const { return window_; }

private:
    GLFWwindow* window_ = nullptr;
    unsigned texture_ = 0;
    bool hasImage_ = false;
};

}  // namespace ripple::apps
