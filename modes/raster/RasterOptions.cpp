#include "modes/raster/RasterOptions.h"

#include "modes/raster/RasterMode.h"

namespace bl {

RasterOptions rasterOptions(const Settings& s) {
    using M = RasterMode;
    RasterOptions o;
    o.shadowResolution = static_cast<std::uint32_t>(s.getInt(M::kShadowResolution));
    o.jitter = s.getBool(M::kJitter);
    o.emitterPoints = static_cast<std::uint32_t>(s.getInt(M::kEmitterPoints));
    o.emitterShadowResolution = static_cast<std::uint32_t>(s.getInt(M::kEmitterShadowResolution));
    return o;
}

} // namespace bl
