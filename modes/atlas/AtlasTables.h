// Host-side tables of mode atlas (modes/atlas/AtlasMode.h), built once per scene from the texture
// atlas (core/atlas) and its link to the GPU scene.
//
// Texel areas. The exchange sends each bundle hit's flux to the texel its atlas uv falls in,
// texel = floor(uv * size), and divides by the world area of everything that maps there. That is
// not the atlas's own per-texel area (core/atlas TexelMaps::area: a triangle's area shared evenly
// among the texels it owns), which differs wherever a texel straddles two triangles of a chart and
// at chart borders; the core has no exact one, so it is computed here: each triangle clipped to
// every texel square its uv footprint touches (Sutherland-Hodgman), the clipped uv area scaled by
// the triangle's world area over its uv area. The sum over texels is the scene's area exactly.
#pragma once

#include "atlas/Atlas.h"
#include "atlas/AtlasLink.h"
#include "atlas/TexelCoverage.h"

#include <modes/atlas/AtlasShared.h>
#include <vector>

namespace bl::atlasmode {

struct AtlasTables {
    std::vector<shader::AtlasTriangle> triangles; // per GpuScene triangle
    std::vector<shader::AtlasTexel> texels;       // per texel of all pages
    std::vector<std::int32_t> charts;             // per texel: owning chart, -1 empty
    double totalArea = 0.0;                       // sum of the texels' preimage areas
    std::size_t degenerateTriangles = 0;          // zero uv area: their hits are not exchanged
};

AtlasTables buildAtlasTables(const atlas::Atlas& atlas, const atlas::AtlasLink& link);

using atlas::clippedTriangleArea; // core/atlas/TexelCoverage.h

} // namespace bl::atlasmode
