// Scenes with closed-form answers, built in code so that tests state exactly what they assume.
#pragma once

#include "scene/Scene.h"

namespace bl::test {

// A square of side `size` centred at the origin in the plane y = 0, facing +y.
Mesh makeSquare(float size, std::uint32_t material, glm::vec3 centre = glm::vec3(0.0f));
// A rectangle in the plane y = `height` spanning [x0,x1] x [z0,z1], facing down (-y) if `facingDown`.
Mesh makeRectangle(glm::vec2 lo, glm::vec2 hi, float height, bool facingDown, std::uint32_t material);

// A Lambertian plane of albedo `albedo` lit by a point light of intensity `intensity` at height h
// above the origin, seen obliquely by a camera of `resolution`.
Scene pointLightOverPlane(float albedo, float intensity, float h, int resolution);

} // namespace bl::test
