#include "viewer/Window.h"

#include "base/Error.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <map>

namespace bl::viewer {

namespace {

const std::map<int, std::string>& keyNames() {
    static const std::map<int, std::string> names = [] {
        std::map<int, std::string> m;
        for (int k = GLFW_KEY_A; k <= GLFW_KEY_Z; ++k) m[k] = std::string(1, char('A' + (k - GLFW_KEY_A)));
        for (int k = GLFW_KEY_0; k <= GLFW_KEY_9; ++k) m[k] = std::string(1, char('0' + (k - GLFW_KEY_0)));
        m[GLFW_KEY_SPACE] = "SPACE";
        m[GLFW_KEY_TAB] = "TAB";
        m[GLFW_KEY_ESCAPE] = "ESCAPE";
        m[GLFW_KEY_LEFT_BRACKET] = "LEFT_BRACKET";
        m[GLFW_KEY_RIGHT_BRACKET] = "RIGHT_BRACKET";
        m[GLFW_KEY_MINUS] = "MINUS";
        m[GLFW_KEY_EQUAL] = "EQUAL";
        m[GLFW_KEY_KP_ADD] = "EQUAL";
        m[GLFW_KEY_KP_SUBTRACT] = "MINUS";
        return m;
    }();
    return names;
}

// GLFW reports its errors through a callback; the last one names why init or a window failed.
std::string gLastError;
void onError(int, const char* text) { gLastError = text ? text : ""; }

} // namespace

Window::Window(int width, int height, const std::string& title) {
    glfwSetErrorCallback(onError);
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) {
        throw Error("bundlelab view needs a display and neither DISPLAY nor WAYLAND_DISPLAY is set: run it in a desktop "
                    "session, over `ssh -X`, or headless under `xvfb-run bundlelab view ...`; `bundlelab render` needs "
                    "no display");
    }
    if (!glfwInit()) {
        throw Error("bundlelab view cannot open the display (" + gLastError + "); `bundlelab render` needs no display");
    }
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw Error("bundlelab view: no Vulkan loader usable for a window (" + gLastError + ")");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!mWindow) {
        glfwTerminate();
        throw Error("bundlelab view cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                    " window (" + gLastError + ")");
    }
    glfwSetWindowUserPointer(mWindow, this);
    glfwSetKeyCallback(mWindow, onKey);
    glfwSetCursorPosCallback(mWindow, onCursor);
    glfwSetMouseButtonCallback(mWindow, onButton);
    glfwSetScrollCallback(mWindow, onScroll);
}

Window::~Window() {
    if (mWindow) glfwDestroyWindow(mWindow);
    glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
    std::uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    if (!names) throw Error("bundlelab view: the window system offers no Vulkan surface (" + gLastError + ")");
    return std::vector<std::string>(names, names + n);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    const VkResult r = glfwCreateWindowSurface(instance, mWindow, nullptr, &surface);
    if (r != VK_SUCCESS) throw Error("bundlelab view: cannot create a Vulkan surface (VkResult " + std::to_string(r) + ")");
    return surface;
}

std::vector<InputEvent> Window::poll() {
    glfwPollEvents();
    std::vector<InputEvent> out;
    out.swap(mEvents);
    if (glfwWindowShouldClose(mWindow)) out.push_back({InputEvent::Kind::Close});
    return out;
}

bool Window::closeRequested() const { return glfwWindowShouldClose(mWindow); }

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(mWindow, title.c_str()); }

void Window::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(mWindow, &width, &height); }

bool Window::held(const std::string& key) const {
    for (const auto& [code, name] : keyNames()) {
        if (name == key && glfwGetKey(mWindow, code) == GLFW_PRESS) return true;
    }
    return false;
}

void Window::onKey(GLFWwindow* w, int key, int, int action, int mods) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    const auto it = keyNames().find(key);
    if (it == keyNames().end()) return;
    InputEvent e;
    e.kind = InputEvent::Kind::Key;
    e.key = it->second;
    e.shift = (mods & GLFW_MOD_SHIFT) != 0;
    self->mEvents.push_back(e);
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    for (int b = 0; b < 2; ++b) {
        if (self->mDragging[b]) {
            InputEvent e;
            e.kind = InputEvent::Kind::Drag;
            e.button = b;
            e.dx = x - self->mLastX;
            e.dy = y - self->mLastY;
            self->mEvents.push_back(e);
        }
    }
    self->mLastX = x;
    self->mLastY = y;
}

void Window::onButton(GLFWwindow* w, int button, int action, int) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    const int b = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : -1;
    if (b < 0) return;
    self->mDragging[b] = action == GLFW_PRESS;
    glfwGetCursorPos(w, &self->mLastX, &self->mLastY);
}

void Window::onScroll(GLFWwindow* w, double dx, double dy) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    InputEvent e;
    e.kind = InputEvent::Kind::Scroll;
    e.dx = dx;
    e.dy = dy;
    self->mEvents.push_back(e);
}

} // namespace bl::viewer
