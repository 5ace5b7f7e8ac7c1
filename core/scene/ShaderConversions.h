// The scene model as the shared host/device structs (shaders/shared/GpuTypes.h) see it, for the
// GPU modes and the CPU reference alike.
#pragma once

#include "scene/Light.h"
#include "scene/Material.h"

#include <shared/GpuTypes.h>

namespace bl {

shader::GpuLight toGpuLight(const Light& light);
shader::GpuMaterial toGpuMaterial(const Material& material);

} // namespace bl
