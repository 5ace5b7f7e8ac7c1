// The scene model as the shared host/device structs (shaders/shared/GpuTypes.h) see it, for the
// GPU modes and the CPU reference alike.
#pragma once

#include "scene/Light.h"
#include "scene/Material.h"

#include <shared/GpuTypes.h>

namespace bl {

shader::GpuLight toGpuLight(const Light& light);

// The cosine of a spot's cone half-angle as every mode tests it: a 32-bit float.
float spotCosOuter(float coneAngleDegrees);

// How many float steps (2^-24, the spacing just below 1) lie between that cosine and 1. A point's
// direction is tested against it as a dot product of normalized floats, itself off by a few such
// steps, so a cone a few steps wide is lit by rounding noise or not at all.
double spotConeSteps(float coneAngleDegrees);
// Below this many steps a spot's lit area renders more than 10 % off: loaders refuse the cone.
inline constexpr double kMinSpotConeSteps = 10.0;
shader::GpuMaterial toGpuMaterial(const Material& material);

} // namespace bl
