#include "scene/ScenePrecision.h"

#include "base/Error.h"
#include "scene/Scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bl {

namespace {

std::string describe(const glm::vec3& v) {
    return "(" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + ")";
}

std::string where(const Scene& scene) {
    return scene.path.empty() ? std::string("scene") : scene.path;
}

// Finite and within kMaxCoordinate, or an Error naming `what` and the value.
void requireCoordinate(const Scene& scene, const glm::vec3& v, const std::string& what) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(v[i]) || std::abs(double(v[i])) > kMaxCoordinate) {
            throw Error(where(scene) + ": " + what + " " + describe(v) +
                        " is not representable: coordinates must be "
                        "finite and within +-" +
                        formatNumber(kMaxCoordinate) +
                        " (float overflows in squared areas beyond); choose a larger length unit");
        }
    }
}

double maxAbs(const glm::vec3& v) {
    return std::max({std::abs(double(v.x)), std::abs(double(v.y)), std::abs(double(v.z))});
}

} // namespace

void requireRepresentable(const Scene& scene) {
    for (const Mesh& m : scene.meshes) {
        const std::string mesh =
            "mesh '" + m.name + "'" + (m.sourceFile.empty() ? "" : " (" + m.sourceFile + ")");
        for (std::size_t v = 0; v < m.positions.size(); ++v) {
            requireCoordinate(scene, m.positions[v], mesh + " vertex " + std::to_string(v));
        }
        for (const RigidKeyframe& k : m.animation.keys()) {
            requireCoordinate(scene, k.translate, mesh + " keyframe translate");
        }
    }
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const std::string light = "light " + std::to_string(i + 1) + " position";
        requireCoordinate(scene, scene.lights[i].position, light);
        for (const LightKeyframe& k : scene.lights[i].keys) {
            requireCoordinate(scene, k.position, light + " (keyframe)");
        }
    }
    requireCoordinate(scene, scene.camera.pose.position, "camera position");
    requireCoordinate(scene, scene.camera.pose.target, "camera target");
    for (const CameraKeyframe& k : scene.camera.keys) {
        requireCoordinate(scene, k.pose.position, "camera keyframe position");
        requireCoordinate(scene, k.pose.target, "camera keyframe target");
    }

    const Bounds b = scene.bounds();
    if (b.empty()) {
        return; // nothing to resolve (loaders refuse a scene without triangles themselves)
    }
    const double diameter = glm::length(glm::dvec3(b.hi) - glm::dvec3(b.lo));
    if (diameter < kMinDiameter) {
        throw Error(where(scene) + ": the geometry spans " + formatNumber(diameter) +
                    ", below the smallest extent " + "float renders (" +
                    formatNumber(kMinDiameter) +
                    ": squared areas underflow below); choose a smaller length unit");
    }
    // The float step at the largest coordinate is the error every vertex, hit point and matrix
    // carries there.
    const double largest = std::max(maxAbs(b.lo), maxAbs(b.hi));
    const float at = static_cast<float>(largest);
    const double step =
        double(std::nextafter(at, std::numeric_limits<float>::infinity())) - double(at);
    if (step > std::ldexp(diameter, -kMinResolvedBits)) {
        throw Error(where(scene) + ": the geometry spans " + formatNumber(diameter) + " but lies " +
                    formatNumber(largest) + " from the origin, where float coordinates step by " +
                    formatNumber(step) + " (more than 2^-" + std::to_string(kMinResolvedBits) +
                    " of its size): its shape is lost on loading; move it nearer the origin (the "
                    "scene file's "
                    "translate, or the mesh file's coordinates)");
    }
}

bool recentreFarScene(Scene& scene) {
    const Bounds b = scene.bounds();
    if (b.empty()) {
        return false;
    }
    const glm::dvec3 lo(b.lo), hi(b.hi);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    if (glm::length(centre) <= kRecentreRadii * 0.5 * glm::length(hi - lo)) {
        return false;
    }
    translateScene(scene, -centre);
    scene.origin += centre;
    return true;
}

} // namespace bl
