#include "gpu/EmitterPointSampler.h"

#include <shared/Random.h>

#include <algorithm>
#include <cmath>

namespace bl::gpu {

namespace {
constexpr std::uint32_t kEmitterStreamKey = 0x27d4eb2fu; // independent of every other stream's key

float meanRadiance(const glm::vec3& emission) { return (emission.x + emission.y + emission.z) / 3.0f; }

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
} // namespace

EmitterPointSampler::EmitterPointSampler(const Scene& scene) : mScene(&scene) {
    std::vector<float> power;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (!mesh.emissive()) {
            continue;
        }
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            const glm::vec3 a = mesh.positions[tri.x];
            // Rigid animation keeps areas, so the power of a triangle is that of its static shape.
            const float area = 0.5f * glm::length(glm::cross(mesh.positions[tri.y] - a, mesh.positions[tri.z] - a));
            if (area > 0.0f && std::isfinite(area)) {
                mTriangles.push_back({m, t});
                // A non-finite radiance (never from a file: the loaders refuse it) draws by area, so
                // its infinite samples reach the image's lost-work count instead of a throw here.
                const float weight = meanRadiance(mesh.emission) * area;
                power.push_back(std::isfinite(weight) ? weight : area);
            }
        }
    }
    mByPower = Distribution1D(power);
    if (mByPower.empty()) {
        mTriangles.clear();
        return;
    }
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
        const std::size_t i = mByPower.sampleDiscrete(std::min(stratum, 0x1.fffffep-1f));
        const Mesh& mesh = mScene->meshes[mTriangles[i].mesh];
        const glm::uvec3 tri = mesh.triangles[mTriangles[i].triangle];
        const glm::mat4 toWorld = mesh.animation.at(time);
        const glm::vec3 a = transformPoint(toWorld, mesh.positions[tri.x]);
        const glm::vec3 b = transformPoint(toWorld, mesh.positions[tri.y]);
        const glm::vec3 c = transformPoint(toWorld, mesh.positions[tri.z]);
        // Uniform on the triangle (the square-root warp of the unit square).
        const float su = std::sqrt(shader::blHashRandom(key, 3 * k + 1));
        const float v = shader::blHashRandom(key, 3 * k + 2);
        const float wa = 1.0f - su;
        const float wb = v * su;
        shader::GpuEmitterPoint p{};
        p.position = wa * a + wb * b + (1.0f - wa - wb) * c;
        p.normal = glm::normalize(glm::cross(b - a, c - a)); // counter-clockwise: the front face
        p.emission = mesh.emission;
        p.areaPdf = shader::blEmitterAreaPdf(mesh.emission, mInversePower);
        p.cubeCentre = p.position + lift * p.normal;
        points.push_back(p);
    }
    return points;
}

} // namespace bl::gpu
