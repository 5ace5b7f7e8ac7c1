// The unoccluded irradiance of the environment for every normal,
//   E(n) = integral over n's hemisphere of L_e(d) (n.d) dd,
// tabulated once per environment map: the control variate of skylight's estimator
// (control_variate = on: bundles then estimate only what occluders remove, SkylightMode.h).
//
// Table: E at normals on a lat-long grid of kWidth x kHeight (column i at u = i / kWidth, row j at
// v = j / (kHeight - 1), so both poles are rows; the EnvMap.h parameterisation without rotation),
// read bilinearly (longitude wraps; blSkylightIrradianceTaps in SkylightShared.h, shared with the
// shader). Each entry is a quadrature over the map: every texel (or 2x2 blocks of texels for maps
// of more than kQuadraturePoints texels) at its centre direction with its exact lat-long solid
// angle; texel-centre quadrature of the bilinearly filtered map is exact for a constant weight.
// Error (SkylightIrradianceTable test): against the full-resolution sum over every texel, mean
// 2.5e-4 / max 1.2e-3 relative on the Vogl probe, 3.6e-4 / 2.4e-3 on the classroom sky; against
// an analytic linear sky at most 9.4e-4 (the bilinear lookup between table normals). That is the
// bias control_variate = on adds to the Lambert part. Built in ~0.5-1.5 s on 2 cores.
#pragma once

#include "scene/Environment.h"

#include <glm/glm.hpp>
#include <vector>

namespace bl {

class IrradianceTable {
public:
    static constexpr int kWidth = 128; // = shader::kSkylightIrradianceWidth (checked in the .cpp)
    static constexpr int kHeight = 65;
    static constexpr std::size_t kQuadraturePoints = 1 << 17; // larger maps are summed in 2x2 blocks

    explicit IrradianceTable(const Environment& env);

    // E(n) for a unit world-space normal, bilinear between the table's normals (as the shader).
    glm::vec3 lookup(const glm::vec3& n) const;
    // Table entries, row-major, rgb + 0 (the GPU's layout).
    const std::vector<glm::vec4>& entries() const { return mEntries; }
    // The same quadrature at each normal, every texel of the map (no blocks, no table): for tests.
    static std::vector<glm::vec3> bruteForce(const Environment& env, const std::vector<glm::vec3>& normals);

private:
    std::vector<glm::vec4> mEntries;
};

} // namespace bl
