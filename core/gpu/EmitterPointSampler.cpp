#include "gpu/EmitterPointSampler.h"

#include "base/Error.h"

#include <shared/Random.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bl::gpu {

namespace {
constexpr std::uint32_t kEmitterStreamKey = 0x27d4eb2fu; // independent of every other stream's key

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
} // namespace

EmitterPointSampler::EmitterPointSampler(const Scene& scene) : mScene(&scene) {
    std::vector<double> power;
    std::vector<float> areas;
    bool finiteRadiance = true;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (!mesh.emissive()) {
            continue;
        }
        const float mean = shader::blEmitterMeanRadiance(mesh.emission);
        finiteRadiance = finiteRadiance && std::isfinite(mean);
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            const glm::vec3 a = mesh.positions[tri.x];
            // Rigid animation keeps areas, so the power of a triangle is that of its static shape.
            const float area = 0.5f * glm::length(glm::cross(mesh.positions[tri.y] - a, mesh.positions[tri.z] - a));
            if (area > 0.0f && std::isfinite(area)) {
                mTriangles.push_back({m, t});
                power.push_back(double(mean) * area);
                areas.push_back(area);
            }
        }
    }
    if (mTriangles.empty()) {
        return;
    }
    if (!finiteRadiance) {
        // A non-finite radiance (never from a file: the loaders refuse it) is drawn by area, so its
        // infinite samples reach the image's lost-work count instead of a throw here.
        mByPower = Distribution1D(areas);
        mInversePower = static_cast<float>(1.0 / mByPower.total());
        return;
    }
    // p_A = mean(L_e) / Phi on the GPU needs each power, Phi and 1 / Phi as normal floats: a
    // radiance near FLT_MAX over a few units of area (or a vanishing one) would turn every point's
    // light into 0, infinity or NaN. Refused, naming the power.
    double total = 0.0;
    for (double p : power) total += p;
    constexpr double kMax = std::numeric_limits<float>::max();
    if (!(total < kMax) || !(1.0 / total < kMax)) {
        char value[32];
        std::snprintf(value, sizeof(value), "%.3g", total);
        throw Error("emitter points: the emitters' power (mean radiance x area, summed over " +
                    std::to_string(mTriangles.size()) + " triangles) is " + value +
                    ", beyond what a float represents; scale the scene's emission (the images are linear in it)");
    }
    mByPower = Distribution1D(std::vector<float>(power.begin(), power.end()));
    mInversePower = static_cast<float>(1.0 / mByPower.total());
}

std::vector<shader::GpuEmitterPoint> EmitterPointSampler::sample(std::uint32_t count, std::uint32_t seed,
                                                                 std::uint32_t iteration, double time,
                                                                 float lift) const {
    std::vector<shader::GpuEmitterPoint> points;
    if (empty()) {
        return points;
    }
    points.reserve(count);
    const std::uint32_t key = shader::blHash(seed ^ kEmitterStreamKey) ^ shader::blHash(iteration);
    for (std::uint32_t k = 0; k < count; ++k) {
        const float stratum = (float(k) + shader::blHashRandom(key, 3 * k)) / float(count);
        points.push_back(point(stratum, {shader::blHashRandom(key, 3 * k + 1), shader::blHashRandom(key, 3 * k + 2)},
                               time, lift));
    }
    return points;
}

shader::GpuEmitterPoint EmitterPointSampler::point(float power, glm::vec2 u, double time, float lift,
                                                   float* coordinateScale) const {
    const std::size_t i = mByPower.sampleDiscrete(std::min(power, 0x1.fffffep-1f));
    const Mesh& mesh = mScene->meshes[mTriangles[i].mesh];
    const glm::uvec3 tri = mesh.triangles[mTriangles[i].triangle];
    const glm::mat4 toWorld = mesh.animation.at(time);
    const glm::vec3 a = transformPoint(toWorld, mesh.positions[tri.x]);
    const glm::vec3 b = transformPoint(toWorld, mesh.positions[tri.y]);
    const glm::vec3 c = transformPoint(toWorld, mesh.positions[tri.z]);
    if (coordinateScale) {
        const glm::vec3 m = glm::max(glm::max(glm::abs(a), glm::abs(b)), glm::abs(c));
        *coordinateScale = std::max({m.x, m.y, m.z});
    }
    // Uniform on the triangle (the square-root warp of the unit square).
    const float su = std::sqrt(u.x);
    const float wa = 1.0f - su;
    const float wb = u.y * su;
    shader::GpuEmitterPoint p{};
    p.position = wa * a + wb * b + (1.0f - wa - wb) * c;
    p.normal = glm::normalize(glm::cross(b - a, c - a)); // counter-clockwise: the front face
    p.emission = mesh.emission;
    p.areaPdf = shader::blEmitterAreaPdf(mesh.emission, mInversePower);
    p.cubeCentre = p.position + lift * p.normal;
    return p;
}

} // namespace bl::gpu
