// atlas's settings read once, typed (AtlasModeOptions.cpp; atlas::AtlasOptions are the atlas
// generator's): what setScene(), iterate(), resolve(), plan() and the first shot's choice use, so
// that none re-reads a setting as a string.
#pragma once

#include "bundle/DirectionSampler.h"
#include "config/Settings.h"

#include <cstdint>
#include <string>

namespace bl {

struct AtlasModeOptions {
    std::uint32_t atlasResolution = 0;     // atlas_resolution: side of an atlas page
    std::uint32_t bundleResolution = 0;    // bundle_resolution
    DirectionSequence directions = DirectionSequence::Halton; // directions
    std::uint32_t strata = 0;              // strata (stratified directions)
    double importanceOffset = 0.0;         // importance_offset
    double weighting = 0.0;                // weighting: direction j weighs j^k
    bool bounce = false;                   // transfer = bounce (else interleaved)
    std::uint32_t bounceDirections = 0;    // bounce_directions: per pass
    std::uint32_t maxSegments = 0;         // max_segments (transfer = bounce)
    std::uint32_t viewSamples = 0;         // view_samples
    bool bilinear = false;                 // bilinear
    std::uint32_t shadowResolution = 0;    // shadow_resolution
    std::uint32_t lightSamples = 0;        // light_samples: sample points per texel side (n x n)
    std::uint64_t memoryCapBytes = 0;      // memory_cap_mib, in bytes
    std::uint32_t poolNodesPerPixel = 0;   // pool_nodes_per_pixel: the bundle pool's first size
    std::string glossy;                    // glossy: transfer | gather | off
    std::uint32_t delayIndirect = 0;       // delay_indirect
    std::string firstShot;                 // first_shot: auto | on | off
    bool shotAllSamples = false;           // shot_samples = all (else one sample point per texel and shot)
    std::uint32_t emitterPoints = 0;       // emitter_points
    std::uint32_t emitterShadowResolution = 0;
    std::uint32_t environmentShots = 0;    // environment_shots: the environment's shot directions per direction
    std::uint32_t environmentShadowResolution = 0; // environment_shadow_resolution: their depth maps' side

    // The scale of the direct atlas's light in the sender: none when bounce-by-bounce transfer
    // stops at one segment (max_segments = 1: emitters seen only).
    float directScale() const { return bounce && maxSegments == 1 ? 0.0f : 1.0f; }
};

// The options of validated settings (atlas's parameter table: AtlasPlan.cpp).
AtlasModeOptions atlasModeOptions(const Settings& settings);

} // namespace bl
