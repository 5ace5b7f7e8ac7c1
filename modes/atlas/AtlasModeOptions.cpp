#include "modes/atlas/AtlasModeOptions.h"

#include "modes/atlas/AtlasMode.h"

namespace bl {

AtlasModeOptions atlasModeOptions(const Settings& s) {
    using M = AtlasMode;
    const auto uint32Of = [&](const char* key) { return static_cast<std::uint32_t>(s.getInt(key)); };
    AtlasModeOptions o;
    o.atlasResolution = uint32Of(M::kAtlasResolution);
    o.bundleResolution = uint32Of(M::kBundleResolution);
    o.directions = directionSequenceNamed(s.getString(M::kDirections));
    o.strata = uint32Of(M::kStrata);
    o.importanceOffset = s.getDouble(M::kImportanceOffset);
    o.weighting = s.getDouble(M::kWeighting);
    o.bounce = s.getString(M::kTransfer) == "bounce";
    o.bounceDirections = uint32Of(M::kBounceDirections);
    o.maxSegments = uint32Of(M::kMaxSegments);
    o.viewSamples = uint32Of(M::kViewSamples);
    o.bilinear = s.getBool(M::kBilinear);
    o.shadowResolution = uint32Of(M::kShadowResolution);
    o.lightSamples = uint32Of(M::kLightSamples);
    o.memoryCapBytes = static_cast<std::uint64_t>(s.getInt(M::kMemoryCap)) << 20;
    o.poolNodesPerPixel = uint32Of(M::kPoolNodes);
    o.glossy = s.getString(M::kGlossy);
    o.delayIndirect = uint32Of(M::kDelayIndirect);
    o.firstShot = s.getString(M::kFirstShot);
    o.shotAllSamples = s.getString(M::kShotSamples) == "all";
    o.emitterPoints = uint32Of(M::kEmitterPoints);
    o.emitterShadowResolution = uint32Of(M::kEmitterShadowResolution);
    o.environmentShots = uint32Of(M::kEnvironmentShots);
    o.environmentShadowResolution = uint32Of(M::kEnvironmentShadowResolution);
    return o;
}

} // namespace bl
