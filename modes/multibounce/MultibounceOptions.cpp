#include "modes/multibounce/MultibounceOptions.h"

#include "modes/EnvironmentShadowParameters.h"

#include "modes/multibounce/MultibounceMode.h"

namespace bl {

MultibounceOptions multibounceOptions(const Settings& s) {
    using M = MultibounceMode;
    const auto uint32Of = [&](const char* key) { return static_cast<std::uint32_t>(s.getInt(key)); };
    MultibounceOptions o;
    o.bundleCount = uint32Of(M::kBundleCount);
    o.pathsPerPixel = uint32Of(M::kPathsPerPixel);
    o.bundleResolution = uint32Of(M::kBundleResolution);
    o.directions = directionSequenceNamed(s.getString(M::kDirections));
    o.maxSegments = uint32Of(M::kMaxSegments);
    o.rrSegments = uint32Of(M::kRrSegments);
    o.shadowResolution = uint32Of(M::kShadowResolution);
    o.memoryCapBytes = static_cast<std::uint64_t>(s.getInt(M::kMemoryCap)) << 20;
    o.imperfect = s.getString(M::kBundles) == "imperfect";
    o.points = uint32Of(M::kPoints);
    o.splatScale = s.getDouble(M::kSplatScale);
    o.splatUvCentre = s.getString(M::kSplatUv) == "centre";
    o.emitterSampling = s.getString(M::kEmitterSampling);
    o.emitterPoints = uint32Of(M::kEmitterPoints);
    o.environmentShots = uint32Of(kEnvironmentShotsKey);
    o.environmentShadowResolution = uint32Of(kEnvironmentShadowResolutionKey);
    o.emitterShadowResolution = uint32Of(M::kEmitterShadowResolution);
    return o;
}

} // namespace bl
