// Orthographic frames for bundles: along a direction, covering a bounding sphere or a set of
// points, with an optional rotation about the direction (decorrelates aliasing across bundles).
#pragma once

#include "base/Bounds.h"
#include "scene/ScenePrecision.h"

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>
#include <shared/BundleTypes.h>
#include <vector>

namespace bl {

// Depth tolerance of a bundle in units of the scene's bounding radius: fragments this close to a
// point's own depth along its ray count as the point itself. 1e-5 of the radius is ~80 float ulps
// of any coordinate inside the sphere, and below any modelled feature: the clearance every mode
// and the reference keep (ScenePrecision.h).
inline constexpr float kBundleDepthEpsilon = kRelativeClearance;
// ...but never below this many float steps of the largest coordinate in the sphere: far from the
// origin every position carries an error of its magnitude's ulp (10^4 radii away one step is
// 6e-4 of the radius, 60x the relative tolerance), and so does every depth measured from it.
inline constexpr float kBundleDepthUlps = 4.0f;

// The depth tolerance of a bundle over the sphere (center, radius).
float bundleDepthEpsilon(const glm::vec3& center, float radius);

// A right-handed basis for direction d: axisX, axisY = cross(d, axisX), d, rotated by `rotation`
// radians about d.
void bundleAxes(const glm::vec3& direction, float rotation, glm::vec3& axisX, glm::vec3& axisY);

// resolution x resolution pixels covering the sphere (center, radius) seen along `direction`.
shader::BundleFrame bundleFrameForSphere(const glm::vec3& direction, float rotation, const glm::vec3& center,
                                         float radius, std::uint32_t resolution);

// Pixels of the same size as `resolution` across the points' largest extent, covering just the
// points' projections (the camera-visible points of [TO12s] B.1); depth range of the sphere.
shader::BundleFrame bundleFrameForPoints(const glm::vec3& direction, float rotation, const std::vector<glm::vec3>& points,
                                         const glm::vec3& sceneCenter, float sceneRadius, std::uint32_t resolution);

// The sub-frame of pixels [x0, x0 + width) x [y0, y0 + height): the same origin and an integer
// offset (tileX, tileY), so a tile projects every point exactly as its frame does.
shader::BundleFrame bundleTile(const shader::BundleFrame& frame, std::uint32_t x0, std::uint32_t y0,
                               std::uint32_t width, std::uint32_t height);

// The viewport a build of the frame (or tile) rasterizes with: the whole grid's, sized to powers of
// two and placed at minus the tile's offset, so clip -> window is exact and every tile clips as
// the whole frame (shaders/bundle/Projection.glsl, blBundleClipPosition).
VkViewport bundleViewport(const shader::BundleFrame& frame);

// Continuous pixel coordinates (of the tile, for a tile) and depth of point p in the frame.
glm::vec3 bundleProject(const shader::BundleFrame& frame, const glm::vec3& p);

} // namespace bl
