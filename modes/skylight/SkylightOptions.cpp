#include "modes/skylight/SkylightOptions.h"

#include "modes/skylight/SkylightMode.h"

namespace bl {

SkylightOptions skylightOptions(const Settings& s) {
    using M = SkylightMode;
    SkylightOptions o;
    o.bundleResolution = static_cast<std::uint32_t>(s.getInt(M::kBundleResolution));
    o.directions = directionSequenceNamed(s.getString(M::kDirections));
    o.importanceOffset = s.getDouble(M::kImportanceOffset);
    o.strata = static_cast<std::uint32_t>(s.getInt(M::kStrata));
    o.fitVisible = s.getString(M::kFit) == "visible";
    o.rotate = s.getBool(M::kRotate);
    o.memoryCapBytes = static_cast<std::uint64_t>(s.getInt(M::kMemoryCap)) << 20;
    o.depthMapVisibility = s.getString(M::kVisibility) == "depth_map";
    o.controlVariate = s.getString(M::kControlVariate) == "on";
    o.glossyControl = s.getString(M::kGlossyControl) == "on";
    o.bundleBackend = s.getString(M::kBundleBackend);
    o.gbufferReuse = static_cast<std::uint32_t>(s.getInt(M::kGBufferReuse));
    return o;
}

} // namespace bl
