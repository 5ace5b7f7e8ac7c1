#include "bundle/BundleFrame.h"

#include "base/Error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <shared/Frame.h>

namespace bl {

void bundleAxes(const glm::vec3& direction, float rotation, glm::vec3& axisX, glm::vec3& axisY) {
    glm::vec3 t, b;
    shader::blOrthonormalBasis(direction, t, b);
    const float c = std::cos(rotation), s = std::sin(rotation);
    axisX = glm::normalize(c * t + s * b);
    // (axisX, axisY, direction) is right-handed with y pointing down the image, so a triangle
    // whose front faces -direction is front-facing to the rasterizer (counter-clockwise).
    axisY = glm::normalize(glm::cross(direction, axisX));
}

float bundleDepthEpsilon(const glm::vec3& center, float radius) {
    const float largest = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)}) + radius;
    const float step = std::nextafter(largest, std::numeric_limits<float>::infinity()) - largest;
    return std::max(kBundleDepthEpsilon * radius, kBundleDepthUlps * step);
}

namespace {
shader::BundleFrame makeFrame(const glm::vec3& direction, const glm::vec3& axisX, const glm::vec3& axisY,
                              glm::vec2 lo, float pixelSize, std::uint32_t width, std::uint32_t height,
                              const glm::vec3& sceneCenter, float sceneRadius) {
    if (!(pixelSize > 0.0f) || width == 0 || height == 0) {
        throw Error("bundle frame: empty extent");
    }
    shader::BundleFrame f{};
    f.direction = direction;
    f.axisX = axisX;
    f.axisY = axisY;
    f.pixelSize = pixelSize;
    f.width = width;
    f.height = height;
    f.gridWidth = width;
    f.gridHeight = height;
    // origin: the frame's corner, on the plane through the sphere centre (depth measured from it).
    const glm::vec3 c = sceneCenter;
    f.origin = c + (lo.x - glm::dot(c, axisX)) * axisX + (lo.y - glm::dot(c, axisY)) * axisY;
    // Depths of the scene lie in [-radius, radius] about the centre; a margin keeps the clip
    // planes off any geometry.
    f.depthNear = -1.01f * sceneRadius;
    f.depthFar = 1.01f * sceneRadius;
    f.depthEpsilon = bundleDepthEpsilon(sceneCenter, sceneRadius);
    return f;
}
} // namespace

shader::BundleFrame bundleFrameForSphere(const glm::vec3& direction, float rotation, const glm::vec3& center,
                                         float radius, std::uint32_t resolution) {
    glm::vec3 ax, ay;
    bundleAxes(direction, rotation, ax, ay);
    const float r = std::max(radius, 1e-30f);
    glm::vec2 lo(glm::dot(center, ax) - r, glm::dot(center, ay) - r);
    return makeFrame(direction, ax, ay, lo, 2.0f * r / float(resolution), resolution, resolution, center, r);
}

shader::BundleFrame bundleFrameForPoints(const glm::vec3& direction, float rotation,
                                         const std::vector<glm::vec3>& points, const glm::vec3& sceneCenter,
                                         float sceneRadius, std::uint32_t resolution) {
    if (points.empty()) {
        return bundleFrameForSphere(direction, rotation, sceneCenter, sceneRadius, resolution);
    }
    glm::vec3 ax, ay;
    bundleAxes(direction, rotation, ax, ay);
    // The projections' bounds over chunks of points in parallel: min and max do not depend on the
    // order, so the frame is the same bit for bit as a serial loop's (bidir fits 21+ frames to a
    // frame's 230k G-buffer points: 9.5 ms serial on one EPYC core, most of the 26 ms a frame
    // spent in "bundles (wall)" on an H100 besides its G-buffer read-back).
    using Box = std::pair<glm::vec2, glm::vec2>;
    const Box empty{glm::vec2(std::numeric_limits<float>::max()), glm::vec2(std::numeric_limits<float>::lowest())};
    const auto [lo0, hi] = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, points.size(), 16384), empty,
        [&](const tbb::blocked_range<std::size_t>& range, Box box) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const glm::vec2 q(glm::dot(points[i], ax), glm::dot(points[i], ay));
                box.first = glm::min(box.first, q);
                box.second = glm::max(box.second, q);
            }
            return box;
        },
        [](const Box& a, const Box& b) { return Box{glm::min(a.first, b.first), glm::max(a.second, b.second)}; });
    glm::vec2 lo = lo0;
    // Half a pixel of margin on every side, so points on the boundary fall inside.
    const float extent = std::max(std::max(hi.x - lo.x, hi.y - lo.y), 1e-6f * sceneRadius);
    const float pixel = extent / float(resolution - 1);
    lo -= 0.5f * pixel;
    const auto w = static_cast<std::uint32_t>(std::ceil((hi.x - lo.x) / pixel + 0.5f));
    const auto h = static_cast<std::uint32_t>(std::ceil((hi.y - lo.y) / pixel + 0.5f));
    return makeFrame(direction, ax, ay, lo, pixel, std::clamp(w, 1u, resolution), std::clamp(h, 1u, resolution),
                     sceneCenter, sceneRadius);
}

shader::BundleFrame bundleTile(const shader::BundleFrame& frame, std::uint32_t x0, std::uint32_t y0,
                               std::uint32_t width, std::uint32_t height) {
    if (x0 + width > frame.width || y0 + height > frame.height || width == 0 || height == 0) {
        throw Error("bundle tile: " + std::to_string(width) + "x" + std::to_string(height) + " at " +
                    std::to_string(x0) + "," + std::to_string(y0) + " outside its " + std::to_string(frame.width) +
                    "x" + std::to_string(frame.height) + " frame");
    }
    // The origin stays: a shifted origin (origin + x0 pixelSize axisX in float) rounds differently
    // from the whole frame, and border points fell into no tile or two (defect 3).
    shader::BundleFrame t = frame;
    t.tileX = frame.tileX + x0;
    t.tileY = frame.tileY + y0;
    t.width = width;
    t.height = height;
    return t;
}

VkViewport bundleViewport(const shader::BundleFrame& frame) {
    return {-float(frame.tileX), -float(frame.tileY), float(std::bit_ceil(std::max(frame.gridWidth, 1u))),
            float(std::bit_ceil(std::max(frame.gridHeight, 1u))), 0.0f, 1.0f};
}

glm::vec3 bundleProject(const shader::BundleFrame& frame, const glm::vec3& p) {
    glm::vec3 rel = p - frame.origin;
    return {glm::dot(rel, frame.axisX) / frame.pixelSize - float(frame.tileX),
            glm::dot(rel, frame.axisY) / frame.pixelSize - float(frame.tileY), glm::dot(rel, frame.direction)};
}

} // namespace bl
