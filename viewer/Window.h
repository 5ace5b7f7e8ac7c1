// A desktop window for `bundlelab view` (GLFW, no client API): its Vulkan surface and the input
// since the last poll as a list of events, so that a script (ViewScript.h) can feed the same
// events as a person.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

struct GLFWwindow;

namespace bl::viewer {

struct InputEvent {
    enum class Kind { Key, Drag, Scroll, Resize, Close };
    Kind kind = Kind::Key;
    std::string key;       // Key: "L", "SPACE", "TAB", "ESCAPE", "LEFT_BRACKET", ... (GLFW names)
    bool shift = false;    // Key: with shift held
    int button = 0;        // Drag: 0 left, 1 right
    double dx = 0.0;       // Drag: pixels; Scroll: wheel steps in dy
    double dy = 0.0;
};

class Window {
public:
    // Throws bl::Error with a clear message when there is no display to open a window on.
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // The instance extensions a surface of this window needs.
    static std::vector<std::string> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance) const;

    // Processes the window system's events; returns the input since the last call.
    std::vector<InputEvent> poll();
    bool closeRequested() const;
    void setTitle(const std::string& title);
    // The drawable size in pixels.
    void framebufferSize(int& width, int& height) const;
    // Keys held now, for continuous fly-camera motion ("W", "A", ...).
    bool held(const std::string& key) const;

private:
    static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
    static void onCursor(GLFWwindow* w, double x, double y);
    static void onButton(GLFWwindow* w, int button, int action, int mods);
    static void onScroll(GLFWwindow* w, double dx, double dy);

    GLFWwindow* mWindow = nullptr;
    std::vector<InputEvent> mEvents;
    bool mDragging[2] = {false, false};
    double mLastX = 0.0, mLastY = 0.0;
};

} // namespace bl::viewer
