// skylight's settings read once, typed (SkylightOptions.cpp): what setScene(), iterate() and plan()
// use, so that iterate() re-reads no setting as a string.
#pragma once

#include "bundle/DirectionSampler.h"
#include "config/Settings.h"

#include <cstdint>
#include <string>

namespace bl {

struct SkylightOptions {
    std::uint32_t bundleResolution = 0;      // bundle_resolution
    DirectionSequence directions = DirectionSequence::Halton; // directions
    double importanceOffset = 0.0;           // importance_offset
    std::uint32_t strata = 0;                // strata
    bool fitVisible = false;                 // fit = visible (else the scene's sphere)
    bool rotate = false;                     // rotate: each bundle about its direction
    std::uint64_t memoryCapBytes = 0;        // memory_cap_mib, in bytes
    bool depthMapVisibility = false;         // visibility = depth_map (else the bundle's lists)
    bool controlVariate = false;             // control_variate = on
    bool glossyControl = true;               // glossy_control_variate = on
    std::string bundleBackend;               // bundle_backend: auto | raster | compute
    std::uint32_t gbufferReuse = 1;          // gbuffer_reuse: directions per jittered G-buffer
};

// The options of validated settings (skylight's parameter table: SkylightMode.cpp).
SkylightOptions skylightOptions(const Settings& settings);

} // namespace bl
