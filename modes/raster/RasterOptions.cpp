#include "modes/raster/RasterOptions.h"

#include "modes/EnvironmentShadowParameters.h"
#include "modes/raster/RasterMode.h"

namespace bl {

RasterOptions rasterOptions(const Settings& s) {
    using M = RasterMode;
    RasterOptions o;
    o.shadowResolution = static_cast<std::uint32_t>(s.getInt(M::kShadowResolution));
    o.jitter = s.getBool(M::kJitter);
    o.emitterPoints = static_cast<std::uint32_t>(s.getInt(M::kEmitterPoints));
    o.emitterShadowResolution = static_cast<std::uint32_t>(s.getInt(M::kEmitterShadowResolution));
    o.environmentShots = static_cast<std::uint32_t>(s.getInt(kEnvironmentShotsKey));
    o.environmentShadowResolution = static_cast<std::uint32_t>(s.getInt(kEnvironmentShadowResolutionKey));
    return o;
}

} // namespace bl
