// The path tracer baking an atlas's texels: per texel side, the mean reflected radiance over the
// surface the texel covers, as GPU lightmappers bake a lightmap with samples jittered over each
// texel. The texel-space reference of the atlas mode: its error is measured over every surface the
// atlas holds, not through one view (core/atlas/TexelRadiance.h).
//
// Each sample first picks a point uniformly over the texel's footprint: the atlas triangles that
// touch the texel, clipped to its square (core/atlas/TexelCoverage.h), a piece by world area and a
// point uniformly in it, mapped to the surface by the atlas triangle's barycentrics. The atlas
// mode's texel is the same mean, over the bundle hits that fall in the texel, divided by the same
// world areas (modes/atlas/AtlasTables.h). (The texel's single sample point of TexelMaps would not
// do: where a texel is only partly covered it lies on the surface's edge, and a path from a box's
// edge leaves through it: -10.5 % in the furnace.)
//
// The path from that point is viewed along the side's geometric normal (PathTracer::traceLeaving:
// next-event estimation and MIS as every reference render; the emitted part left out). For a diffuse surface the reflected radiance is the same in
// every direction, so this is the texel's radiance; a glossy surface's direction-dependent part is
// not what an atlas texel holds (the atlas mode gathers it per pixel), and it is baked as seen
// along the normal only.
#pragma once

#include "atlas/Atlas.h"
#include "atlas/TexelRadiance.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"

#include <cstdint>

namespace bl {

struct TexelBakeSettings {
    std::uint32_t samples = 64; // per texel side
    std::uint32_t seed = 0;
    ReferenceSettings reference; // path length, threads, light sampling: as the reference mode's
};

struct TexelBake {
    atlas::TexelRadiance radiance;
    double seconds = 0.0;
    std::uint64_t rays = 0;
    std::uint64_t paths = 0;
    std::uint64_t nonFiniteSamples = 0; // never averaged in (each side's mean is over the finite ones)
    std::uint64_t emptyTexels = 0;      // valid texels no triangle covers with area (left black, as the atlas leaves them)
};

// Bakes every valid texel of `atlas` (an atlas of `scene`; an animated scene is refused).
TexelBake bakeTexels(const Scene& scene, const atlas::Atlas& atlas, const TexelBakeSettings& settings);

} // namespace bl
