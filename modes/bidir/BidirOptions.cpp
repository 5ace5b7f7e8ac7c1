#include "modes/bidir/BidirOptions.h"

#include "modes/bidir/BidirMode.h"

#include <modes/bidir/BidirShared.h>
#include <modes/bidir/Suppression.h>

namespace bl {

namespace {

std::uint32_t strategyOf(const std::string& name) {
    if (name == "vpl") return shader::kBidirStrategyVpl;
    if (name == "bundle") return shader::kBidirStrategyBundle;
    return shader::kBidirStrategyMis;
}

std::uint32_t suppressionOf(const std::string& name) {
    if (name == "clamp") return shader::kBidirSuppressionClamp;
    if (name == "roughness") return shader::kBidirSuppressionRoughness;
    return shader::kBidirSuppressionNone;
}

std::uint32_t uint32Of(const Settings& s, const char* key) { return static_cast<std::uint32_t>(s.getInt(key)); }

} // namespace

bool BidirOptions::suppressesGlossy(const SceneFeatures& f) const {
    // Indirect light needs VPLs: from point/spot lights, or from area emitters (emitter points on).
    const bool vplSources = f.shadowCastingLights() > 0 || (f.emissiveMeshes && emitterPoints > 0);
    return suppression != shader::kBidirSuppressionNone && f.glossy && vplSources;
}

BidirOptions bidirOptions(const Settings& s) {
    using M = BidirMode;
    BidirOptions o;
    o.pairs = uint32Of(s, M::kPairs);
    o.strategyName = s.getString(M::kStrategy);
    o.strategy = strategyOf(o.strategyName);
    o.bounces = uint32Of(s, M::kBounces);
    o.twoBounceClamp = s.getDouble(M::kTwoBounceClamp);
    o.bundleResolution = uint32Of(s, M::kBundleResolution);
    o.directions = directionSequenceNamed(s.getString(M::kDirections));
    o.fitVisible = s.getString(M::kFit) == "visible";
    o.memoryCapBytes = static_cast<std::uint64_t>(s.getInt(M::kMemoryCap)) << 20;
    o.shadowResolution = uint32Of(s, M::kShadowResolution);
    o.vplShadowResolution = uint32Of(s, M::kVplShadowResolution);
    o.vplShadowTaps = uint32Of(s, M::kVplShadowTaps);
    o.rsmVpls = s.getString(M::kVplSource) == "rsm";
    o.rsmResolution = uint32Of(s, M::kRsmResolution);
    o.environmentBundles = uint32Of(s, M::kEnvironmentBundles);
    o.suppressionName = s.getString(M::kSuppression);
    o.suppression = suppressionOf(o.suppressionName);
    o.suppressionNeighbours = s.getDouble(M::kSuppressionNeighbours);
    o.emitterPoints = uint32Of(s, M::kEmitterPoints);
    o.emitterShadowResolution = uint32Of(s, M::kEmitterShadowResolution);
    o.interleave = uint32Of(s, M::kInterleave);
    o.interleaveFilter = s.getString(M::kInterleaveFilter) == "on";
    o.temporal = s.getString(M::kTemporal) == "on";
    o.reprojectAlways = s.getString(M::kReprojection) == "always";
    o.temporalDepthVariance = s.getDouble(M::kTemporalDepthVariance);
    return o;
}

} // namespace bl
