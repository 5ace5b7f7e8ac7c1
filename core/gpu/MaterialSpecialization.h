// Host side of gpu/MaterialSpecialization.glsl: the values of the material specialization
// constants (whether some material has a glossy lobe, an anisotropic one, an albedo texture),
// appended after a pass's own constants.
#pragma once

#include "scene/SceneFeatures.h"

#include <cstddef>
#include <cstdint>
#include <vector>
#include <shared/MaterialSpecialization.h>

namespace bl::gpu {

// Appends the three constants to `specialization`, whose size must be the shader's
// BL_MATERIAL_SPEC_FIRST.
inline void appendMaterialSpecialization(std::vector<std::uint32_t>& specialization, const SceneFeatures& features) {
    const std::size_t first = specialization.size();
    specialization.resize(first + shader::kMaterialSpecCount);
    specialization[first + shader::kMaterialSpecGlossy] = features.glossy ? 1u : 0u;
    specialization[first + shader::kMaterialSpecAnisotropic] = features.anisotropic ? 1u : 0u;
    specialization[first + shader::kMaterialSpecTextured] = features.textured ? 1u : 0u;
}

} // namespace bl::gpu
