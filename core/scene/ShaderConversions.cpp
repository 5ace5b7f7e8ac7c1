#include "scene/ShaderConversions.h"

#include <algorithm>
#include <cmath>

namespace bl {

shader::GpuLight toGpuLight(const Light& l) {
    shader::GpuLight g{};
    g.position = l.position;
    g.intensity = l.intensity;
    g.direction = l.direction;
    g.type = l.type == Light::Type::Spot ? shader::kLightSpot : shader::kLightPoint;
    float inner = glm::radians(std::max(l.coneAngleDegrees - l.falloffDegrees, 0.0f));
    g.cosOuter = spotCosOuter(l.coneAngleDegrees);
    // A hard edge (falloff 0) still needs inner > outer in cosine for the smoothstep division.
    g.cosInner = std::max(std::cos(inner), g.cosOuter + 1e-7f);
    return g;
}

float spotCosOuter(float coneAngleDegrees) { return std::cos(glm::radians(coneAngleDegrees)); }

double spotConeSteps(float coneAngleDegrees) {
    return (1.0 - double(spotCosOuter(coneAngleDegrees))) / std::ldexp(1.0, -24);
}

shader::GpuMaterial toGpuMaterial(const Material& m) {
    shader::GpuMaterial g{};
    g.albedo = m.albedo;
    g.specular = m.specular;
    g.exponentU = m.exponentU;
    g.exponentV = m.exponentV;
    g.albedoTexture = m.albedoTexture >= 0 ? static_cast<std::uint32_t>(m.albedoTexture) : shader::kNoTexture;
    return g;
}

} // namespace bl
