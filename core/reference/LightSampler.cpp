#include "reference/LightSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <shared/Sampling.h>

namespace bl {

LightSampler::LightSampler(const EmbreeScene& geometry, const EnvironmentLight& environment)
    : mGeometry(&geometry), mEnvironment(&environment) {
    const Scene& scene = geometry.scene();
    std::vector<double> power;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        mFirstTriangleOfMesh.push_back(mesh.emissive() ? static_cast<std::int64_t>(mTriangles.size()) : -1);
        if (!mesh.emissive()) {
            continue;
        }
        // Luminance can be 0 for a saturated colour; the largest channel never is.
        const float strength = std::max({mesh.emission.x, mesh.emission.y, mesh.emission.z});
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            glm::vec3 a, b, c;
            geometry.triangle(m, t, a, b, c);
            float area = 0.5f * glm::length(glm::cross(b - a, c - a));
            mTriangles.push_back({m, t, area});
            power.push_back(double(area) * strength);
        }
    }
    // Normalized in double, so emitters near the top of the float range cannot overflow.
    const double largest = power.empty() ? 0.0 : *std::max_element(power.begin(), power.end());
    std::vector<float> weights;
    for (double p : power) weights.push_back(largest > 0.0 ? float(p / largest) : 0.0f);
    mTriangleDistribution = Distribution1D(weights);
    const bool area = !mTriangleDistribution.empty();
    mAreaProbability = area ? (environment.present() ? 0.5f : 1.0f) : 0.0f;
}

LightSample LightSampler::sample(const glm::vec3& p, const glm::vec3& u) const {
    LightSample s;
    float pick = u.x;
    if (pick < mAreaProbability) {
        pick /= mAreaProbability;
        float probability = 0.0f;
        const EmitterTriangle& e = mTriangles[mTriangleDistribution.sampleDiscrete(pick, &probability)];
        glm::vec3 a, b, c;
        mGeometry->triangle(e.mesh, e.tri, a, b, c);
        glm::vec2 bary = shader::blSampleTriangle(glm::vec2(u.y, u.z));
        s.point = (1.0f - bary.x - bary.y) * a + bary.x * b + bary.y * c;
        s.normal = glm::normalize(glm::cross(b - a, c - a));
        s.offsetScale = std::max({glm::length(a), glm::length(b), glm::length(c)});
        glm::vec3 d = s.point - p;
        float d2 = glm::dot(d, d);
        s.distance = std::sqrt(d2);
        if (!(s.distance > 0.0f)) {
            return LightSample{};
        }
        s.direction = d / s.distance;
        float cosLight = -glm::dot(s.normal, s.direction);
        if (cosLight <= 0.0f) {
            return LightSample{}; // the back of a one-sided emitter
        }
        s.radiance = mGeometry->scene().meshes[e.mesh].emission;
        s.pdf = mAreaProbability * probability / e.area * d2 / cosLight;
        return s;
    }
    if (!mEnvironment->present()) {
        return s;
    }
    float pdf = 0.0f;
    s.direction = mEnvironment->sample(glm::vec2(u.y, u.z), &pdf);
    s.distance = std::numeric_limits<float>::infinity();
    s.radiance = mEnvironment->radiance(s.direction);
    s.pdf = (1.0f - mAreaProbability) * pdf;
    return s;
}

float LightSampler::pdfEmitter(std::uint32_t mesh, std::uint32_t tri, const glm::vec3& p, const glm::vec3& q,
                               const glm::vec3& n) const {
    std::int64_t first = mFirstTriangleOfMesh[mesh];
    if (first < 0) {
        return 0.0f;
    }
    const EmitterTriangle& e = mTriangles[static_cast<std::size_t>(first) + tri];
    glm::vec3 d = q - p;
    float d2 = glm::dot(d, d);
    float cosLight = -glm::dot(n, d) / std::sqrt(d2);
    if (cosLight <= 0.0f || e.area <= 0.0f) {
        return 0.0f;
    }
    return mAreaProbability * mTriangleDistribution.probability(static_cast<std::size_t>(first) + tri) / e.area *
           d2 / cosLight;
}

float LightSampler::pdfEnvironment(const glm::vec3& direction) const {
    return mEnvironment->present() ? (1.0f - mAreaProbability) * mEnvironment->pdf(direction) : 0.0f;
}

} // namespace bl
