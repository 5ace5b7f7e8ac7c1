// bidir's settings read once, typed (BidirOptions.cpp): what setScene(), iterate() and plan() use,
// so that none of them re-reads a setting as a string and all three read the same values.
#pragma once

#include "bundle/DirectionSampler.h"
#include "config/Settings.h"
#include "scene/Scene.h"

#include <cstdint>
#include <string>

namespace bl {

struct BidirOptions {
    std::uint32_t pairs = 0;                // pairs_per_frame: VPLs + bundles per frame
    std::string strategyName;               // strategy: vpl | bundle | mis
    std::uint32_t strategy = 0;             // the same as shader::kBidirStrategy*
    std::uint32_t bounces = 1;              // bounces: 1, or 2 (two-bounce paths)
    double twoBounceClamp = 0.0;            // two_bounce_clamp, of the scene's radius
    std::uint32_t bundleResolution = 0;     // bundle_resolution
    DirectionSequence directions = DirectionSequence::Random; // directions: random | halton
    bool fitVisible = false;                // fit = visible (else the scene's sphere)
    std::uint64_t memoryCapBytes = 0;       // memory_cap_mib, in bytes
    std::uint32_t shadowResolution = 0;     // shadow_resolution: the lights' cubes
    std::uint32_t vplShadowResolution = 0;  // vpl_shadow_resolution
    std::uint32_t vplShadowTaps = 0;        // vpl_shadow_taps
    bool rsmVpls = false;                   // vpl_source = rsm (else CPU light paths)
    std::uint32_t rsmResolution = 0;        // rsm_resolution
    std::uint32_t environmentBundles = 0;   // environment_bundles
    std::string suppressionName;            // suppression: none | clamp | roughness
    std::uint32_t suppression = 0;          // the same as shader::kBidirSuppression*
    double suppressionNeighbours = 0.0;     // suppression_neighbours
    std::uint32_t emitterPoints = 0;        // emitter_points
    std::uint32_t emitterShadowResolution = 0;
    std::uint32_t interleave = 1;           // interleave: n x n pixel groups
    bool interleaveFilter = false;          // interleave_filter = on
    bool temporal = false;                  // temporal = on
    bool reprojectAlways = false;           // reprojection = always (else: when the camera moves)
    double temporalDepthVariance = 0.0;     // temporal_depth_variance

    bool twoBounce() const { return bounces >= 2; }
    // Glossy suppression runs only where it can change something: a glossy material lit by a light
    // that casts shadows.
    bool suppressesGlossy(const SceneFeatures& f) const;
};

// The options of validated settings (bidir's parameter table: BidirPlan.cpp).
BidirOptions bidirOptions(const Settings& settings);

} // namespace bl
