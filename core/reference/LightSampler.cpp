#include "reference/LightSampler.h"

#include "reference/SphericalTriangle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <shared/Sampling.h>

namespace bl {

namespace {
// Spherical triangles outside this range of solid angle (sr) fall back to area sampling, as in
// pbrt-v4: below it the spherical construction loses float precision, above it (near 2 pi) too.
constexpr float kMinSphericalSolidAngle = 3e-4f;
constexpr float kMaxSphericalSolidAngle = 6.22f;
} // namespace

LightSampler::LightSampler(const EmbreeScene& geometry, const EnvironmentLight& environment,
                           EmitterSampling emitterSampling)
    : mGeometry(&geometry), mEnvironment(&environment), mEmitterSampling(emitterSampling) {
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

float LightSampler::samplingSolidAngle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b,
                                       const glm::vec3& c) const {
    if (mEmitterSampling != EmitterSampling::SolidAngle) {
        return 0.0f;
    }
    float omega = triangleSolidAngle(p, a, b, c);
    return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle ? omega : 0.0f;
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
        s.normal = glm::normalize(glm::cross(b - a, c - a));
        s.offsetScale = std::max({glm::length(a), glm::length(b), glm::length(c)});
        s.radiance = mGeometry->scene().meshes[e.mesh].emission;
        const float omega = samplingSolidAngle(p, a, b, c);
        glm::vec3 w;
        if (omega > 0.0f && sampleSphericalTriangle(p, a, b, c, glm::vec2(u.y, u.z), w)) {
            // Where the direction meets the triangle's plane.
            float denominator = glm::dot(w, s.normal);
            if (!(denominator < 0.0f)) {
                return LightSample{}; // the back of a one-sided emitter
            }
            s.distance = glm::dot(a - p, s.normal) / denominator;
            if (!(s.distance > 0.0f) || !std::isfinite(s.distance)) {
                return LightSample{};
            }
            s.direction = w;
            s.point = p + s.distance * w;
            s.pdf = mAreaProbability * probability / omega;
            return s;
        }
        glm::vec2 bary = shader::blSampleTriangle(glm::vec2(u.y, u.z));
        s.point = (1.0f - bary.x - bary.y) * a + bary.x * b + bary.y * c;
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
    const std::size_t index = static_cast<std::size_t>(first) + tri;
    const EmitterTriangle& e = mTriangles[index];
    glm::vec3 d = q - p;
    float d2 = glm::dot(d, d);
    float cosLight = -glm::dot(n, d) / std::sqrt(d2);
    if (cosLight <= 0.0f || e.area <= 0.0f) {
        return 0.0f;
    }
    const float selection = mAreaProbability * mTriangleDistribution.probability(index);
    glm::vec3 a, b, c;
    mGeometry->triangle(mesh, tri, a, b, c);
    if (float omega = samplingSolidAngle(p, a, b, c); omega > 0.0f) {
        return selection / omega;
    }
    return selection / e.area * d2 / cosLight;
}

float LightSampler::pdfEnvironment(const glm::vec3& direction) const {
    return mEnvironment->present() ? (1.0f - mAreaProbability) * mEnvironment->pdf(direction) : 0.0f;
}

} // namespace bl
