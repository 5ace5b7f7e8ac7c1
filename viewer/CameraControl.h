// Orbit and fly cameras for `bundlelab view`, driven by the window's (or a script's) input, and
// the pose as the scene file's [camera] block.
#pragma once

#include "scene/Camera.h"
#include "viewer/Window.h"

#include <glm/glm.hpp>
#include <string>

namespace bl::viewer {

class CameraControl {
public:
    enum class Style { Orbit, Fly };

    // `sceneRadius` scales pans, dollies and fly speed to the scene.
    explicit CameraControl(float sceneRadius) : mRadius(sceneRadius) {}

    Style style() const { return mStyle; }
    void toggleStyle() { mStyle = mStyle == Style::Orbit ? Style::Fly : Style::Orbit; }

    // Orbit: left drag turns about the target, right drag pans, the wheel dollies. Fly: left
    // drag looks around. Returns true when the pose changed.
    bool apply(const InputEvent& e, CameraPose& pose) const;
    // Fly: W/S forward and back, A/D sideways, Q/E down and up, for `seconds` of motion. Returns
    // true when the pose changed.
    bool fly(const Window& window, double seconds, CameraPose& pose) const;

    // The camera as a scene file's [camera] block (positions in file coordinates: + origin).
    static std::string tomlBlock(const Camera& camera, const glm::dvec3& origin);

private:
    Style mStyle = Style::Orbit;
    float mRadius;
};

} // namespace bl::viewer
