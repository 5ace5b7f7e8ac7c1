// Uniform sampling of the solid angle a triangle subtends (Arvo 1995, "Stratified Sampling of
// Spherical Triangles", in the robust form of pbrt-v4). Sampling emitters by solid angle removes
// the 1/r^2 variance of area sampling next to a light (the ceiling around a Cornell box lamp).
#pragma once

#include <glm/glm.hpp>

namespace bl {

// Solid angle of triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983).
float triangleSolidAngle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// A unit direction from p, uniform within the spherical triangle; false if it is degenerate.
bool sampleSphericalTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                             glm::vec2 u, glm::vec3& direction);

} // namespace bl
