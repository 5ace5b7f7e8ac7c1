// multibounce's settings read once, typed (MultibounceOptions.cpp): what setScene(), iterate(),
// plan() and trades() use, so that none re-reads a setting as a string.
#pragma once

#include "bundle/DirectionSampler.h"
#include "config/Settings.h"

#include <cstdint>
#include <string>

namespace bl {

struct MultibounceOptions {
    std::uint32_t bundleCount = 0;            // bundle_count: K resident bundles per iteration
    std::uint32_t pathsPerPixel = 0;          // paths_per_pixel
    std::uint32_t bundleResolution = 0;       // bundle_resolution
    DirectionSequence directions = DirectionSequence::Halton; // directions: halton | random
    std::uint32_t maxSegments = 0;            // max_segments
    std::uint32_t rrSegments = 0;             // rr_segments: Russian roulette after this many
    std::uint32_t shadowResolution = 0;       // shadow_resolution
    std::uint64_t memoryCapBytes = 0;         // memory_cap_mib, in bytes
    bool imperfect = false;                   // bundles = imperfect (point splats)
    std::uint32_t points = 0;                 // points: splats per direction
    double splatScale = 0.0;                  // splat_scale
    bool splatUvCentre = false;               // splat_uv = centre (else corners)
    std::string emitterSampling;              // emitter_sampling: bundles | points | mis
    std::uint32_t emitterPoints = 0;          // emitter_points
    std::uint32_t emitterShadowResolution = 0;
    std::uint32_t environmentShots = 0;       // environment_shots: directions toward the environment per iteration
    std::uint32_t environmentShadowResolution = 0;

    // Emitter points per iteration: 0 with emitter_sampling = bundles.
    std::uint32_t emitterPointCount() const { return emitterSampling == "bundles" ? 0u : emitterPoints; }
    // Environment directions per iteration: 0 with emitter_sampling = bundles.
    std::uint32_t environmentShotCount() const { return emitterSampling == "bundles" ? 0u : environmentShots; }
    bool emitterPointsOnly() const { return emitterSampling == "points"; }
};

// The options of validated settings (multibounce's parameter table: MultibounceMode.cpp).
MultibounceOptions multibounceOptions(const Settings& settings);

} // namespace bl
