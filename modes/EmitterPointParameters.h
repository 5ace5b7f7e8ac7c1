// The two settings of emitter points (core/gpu/EmitterPointPass.h), offered under the same keys,
// defaults and ranges by every mode that lights area emitters with them (raster, multibounce,
// bidir, atlas's first shot).
#pragma once

#include "config/Settings.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bl {

inline constexpr const char* kEmitterPointsKey = "emitter_points";
inline constexpr const char* kEmitterShadowResolutionKey = "emitter_shadow_resolution";

// A mode's `params` with the two appended. `perWhat`: what one set of points serves
// ("iteration", "frame", "direction"); `use`: what the mode does with them; `fewestPoints`: 0
// where no points leaves the area lights out, 1 where the mode's chosen sampling needs them.
std::vector<ParamSpec> withEmitterPointParameters(std::vector<ParamSpec> params, const std::string& perWhat,
                                                  const std::string& use, std::int64_t fewestPoints);

} // namespace bl
