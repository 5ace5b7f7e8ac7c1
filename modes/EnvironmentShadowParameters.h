// The two settings of the environment's shadow-mapped directions (bundle/EnvironmentShadowPass.h),
// offered under the same keys, defaults and ranges by every mode that lights points from the
// environment with them (atlas's first shot, multibounce's next-event estimation).
#pragma once

#include "config/Settings.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bl {

inline constexpr const char* kEnvironmentShotsKey = "environment_shots";
inline constexpr const char* kEnvironmentShadowResolutionKey = "environment_shadow_resolution";

// A mode's `params` with the two appended. `perWhat`: what one set of directions serves
// ("iteration", "direction"); `use`: what the mode does with them, and what 0 directions means.
std::vector<ParamSpec> withEnvironmentShadowParameters(std::vector<ParamSpec> params, const std::string& perWhat,
                                                       const std::string& use);

} // namespace bl
