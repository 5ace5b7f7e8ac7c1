// Sample points inside each atlas texel's preimage, for light that mode atlas gathers per texel
// rather than by exchange (point and spot lights by shadow maps, [HHGM10] section 6.5).
//
// A texel stands for the area average over the surface whose atlas uv falls in it (AtlasTables.h),
// so its direct light is that average too, not the value at one point: the texel square is
// sampled on an n x n grid of uv points, each kept where it falls inside one of the triangles that
// touch the texel (so no sample lies off the surface or behind a wall: the texel centre of a
// border texel often does), mapped to world space through that triangle, and weighted by the
// triangle's world area per uv area (a uniform uv grid is then a uniform area sample). A texel
// with area whose grid misses its sliver of triangle gets that triangle's uv centroid instead.
#pragma once

#include "atlas/Atlas.h"
#include "atlas/AtlasLink.h"
#include "scene/Scene.h"

#include <modes/atlas/AtlasShared.h>
#include <vector>

namespace bl::atlasmode {

struct TexelSamples {
    std::vector<shader::AtlasSample> samples; // grouped by texel
    std::vector<std::uint32_t> first;         // per texel, its first sample; first[texels] = samples.size()
};

// `grid`: samples per texel side; positions and normals at scene time `time` (rigid animation).
TexelSamples buildTexelSamples(const Scene& scene, const atlas::Atlas& atlas, const atlas::AtlasLink& link,
                               int grid, double time);

} // namespace bl::atlasmode
