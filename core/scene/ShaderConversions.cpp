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
    float outer = glm::radians(l.coneAngleDegrees);
    float inner = glm::radians(std::max(l.coneAngleDegrees - l.falloffDegrees, 0.0f));
    g.cosOuter = std::cos(outer);
    // A hard edge (falloff 0) still needs inner > outer in cosine for the smoothstep division.
    g.cosInner = std::max(std::cos(inner), g.cosOuter + 1e-7f);
    return g;
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
