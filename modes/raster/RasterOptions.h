// raster's settings read once, typed (RasterOptions.cpp): what setScene(), iterate() and plan() use.
#pragma once

#include "config/Settings.h"

#include <cstdint>

namespace bl {

struct RasterOptions {
    std::uint32_t shadowResolution = 0;        // shadow_resolution: side of each light's cube face
    bool jitter = true;                        // jitter: the sample position moves every iteration
    std::uint32_t emitterPoints = 0;           // emitter_points
    std::uint32_t emitterShadowResolution = 0; // emitter_shadow_resolution
    std::uint32_t environmentShots = 0;        // environment_shots: directions toward the environment per iteration
    std::uint32_t environmentShadowResolution = 0;
};

// The options of validated settings (raster's parameter table: RasterMode.cpp).
RasterOptions rasterOptions(const Settings& settings);

} // namespace bl
