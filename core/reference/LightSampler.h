// Next-event estimation for the CPU reference: emissive triangles (chosen in proportion to their
// power, then a direction uniform in the solid angle the triangle subtends, or a point uniform in
// its area), the environment (by luminance), and point/spot lights (delta lights, all evaluated at
// every vertex). Densities are in solid angle at the shading
// point and include the probability of choosing the light, so MIS can compare them with BRDF
// sampling.
#pragma once

#include "reference/EmbreeScene.h"
#include "sampling/EnvironmentLight.h"
#include "sampling/Distribution.h"

namespace bl {

struct LightSample {
    glm::vec3 direction{0.0f}; // unit, from the shading point toward the light
    float distance = 0.0f;     // to the light point (infinity for the environment)
    glm::vec3 radiance{0.0f};  // emitted radiance arriving along -direction
    float pdf = 0.0f;          // solid angle, selection included; 0 = no sample
    glm::vec3 point{0.0f};     // the light point (area lights)
    glm::vec3 normal{0.0f};    // its front normal (area lights)
    float offsetScale = 0.0f;  // its triangle's coordinate magnitude
};

enum class EmitterSampling { SolidAngle, Area };

class LightSampler {
public:
    LightSampler(const EmbreeScene& geometry, const EnvironmentLight& environment, EmitterSampling emitterSampling);

    bool hasAreaLights() const { return !mTriangles.empty(); }
    // Samples an emissive triangle or the environment as seen from p.
    LightSample sample(const glm::vec3& p, const glm::vec3& u) const;
    // Density (solid angle at p, selection included) of reaching the front of emitter triangle
    // (mesh, tri) at point q with front normal n.
    float pdfEmitter(std::uint32_t mesh, std::uint32_t tri, const glm::vec3& p, const glm::vec3& q,
                     const glm::vec3& n) const;
    float pdfEnvironment(const glm::vec3& direction) const;

private:
    // Solid angle of the triangle from p when it is sampled by solid angle there, else 0 (area
    // sampling: tiny or huge spherical triangles are numerically unreliable).
    float samplingSolidAngle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const;

    struct EmitterTriangle {
        std::uint32_t mesh;
        std::uint32_t tri;
        float area;
    };
    const EmbreeScene* mGeometry;
    const EnvironmentLight* mEnvironment;
    std::vector<EmitterTriangle> mTriangles;
    std::vector<std::int64_t> mFirstTriangleOfMesh; // -1 for non-emissive meshes
    Distribution1D mTriangleDistribution;
    float mAreaProbability = 0.0f; // of choosing the area lights over the environment
    EmitterSampling mEmitterSampling;
};

} // namespace bl
