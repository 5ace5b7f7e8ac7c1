#include "modes/Registry.h"

#include "base/Error.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/bidir/BidirMode.h"
#include "modes/multibounce/MultibounceMode.h"
#include "modes/raster/RasterMode.h"
#include "modes/reference/ReferenceMode.h"
#include "modes/skylight/SkylightMode.h"

namespace bl {

namespace {
const ModeEntry kModes[] = {
    {"atlas", "diffuse radiance exchange in a texture atlas along sorted global ray-bundles [HHGM10 Eq. 3]", true,
     &AtlasMode::parameters, &AtlasMode::create},
    {"bidir", "real-time bidirectional path tracing: VPLs + ray-bundles with MIS, one and two bounces, glossy suppression [TO12 Eq. 3-17]", true,
     &BidirMode::parameters, &BidirMode::create},
    {"multibounce", "global illumination of any path length through K resident omnidirectional bundles [TO12 section 7]",
     true, &MultibounceMode::parameters, &MultibounceMode::create},
    {"raster", "rasterized direct light from point/spot lights (cube shadow maps), emitters, environment",
     true, &RasterMode::parameters, &RasterMode::create},
    {"reference", "CPU path tracer (Embree): ground truth, layers by path length, per-pixel variance", false,
     &ReferenceMode::parameters, &ReferenceMode::create},
    {"skylight", "direct environment light (and ambient occlusion) by global ray-bundles [TO12 section 3]", true,
     &SkylightMode::parameters, &SkylightMode::create},
};
} // namespace

std::span<const ModeEntry> modeRegistry() { return kModes; }

const ModeEntry& findMode(std::string_view name) {
    std::string known;
    for (const ModeEntry& e : kModes) {
        if (e.name == name) {
            return e;
        }
        known += (known.empty() ? "" : ", ") + std::string(e.name);
    }
    throw Error("unknown mode '" + std::string(name) + "' (available: " + known + ")");
}

std::unique_ptr<Mode> createMode(std::string_view name, const std::vector<std::string>& assignments) {
    const ModeEntry& entry = findMode(name);
    Settings settings(entry.parameters());
    for (const std::string& a : assignments) {
        try {
            settings.assign(a);
        } catch (const Error& e) {
            throw Error("mode " + std::string(name) + ": " + e.what()); // which mode's parameter
        }
    }
    return entry.create(settings);
}

} // namespace bl
