// Reflected radiance per texel side of an atlas, so that the atlas mode's solution can be judged
// over every surface, not through one view ([HHGM10] §4; issue: "atlas judged where it is meant
// to win"): the atlas mode reads its texels back (AtlasMode::texelRadiance), the path tracer bakes
// the same texels (reference/TexelBaker.h), as GPU lightmappers bake a lightmap.
//
// What is compared: both hold a texel side's mean over the surface the texel covers (the atlas
// over the bundle hits that land in it, the baker over points jittered across it), so what
// separates them is the atlas's own error, noise and bias, not where in the texel each looks.
#pragma once

#include "atlas/Atlas.h"
#include "image/Image.h"
#include "image/Metrics.h"

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <utility>
#include <vector>

namespace bl::atlas {

struct TexelRadiance {
    int width = 0; // of one page, as TexelMaps
    int height = 0;
    int pages = 1;
    // Side 0 (front: the side the triangle's counter-clockwise corners face) and side 1, per texel
    // (index (page * height + y) * width + x), reflected radiance only (no emission).
    std::array<std::vector<glm::vec3>, 2> side;
    // 1 where the texel's sample is a point of its own (TexelMaps::valid == 1); dilated and empty
    // texels are 0 and take no part in a comparison.
    std::vector<std::uint8_t> valid;

    // Sized as `maps`, every side black, valid as the maps say.
    static TexelRadiance like(const TexelMaps& maps);
    std::size_t texels() const { return valid.size(); }
};

// Error of `test` against `reference` over the texel sides that count: valid texels whose side is
// not black in both (a side nothing reaches, such as a closed box's outside, is no evidence either
// way). Metrics of core/image/Metrics.h (relmse with epsilon 0.01) over those sides, one pixel each.
// Throws when the two are not of the same atlas.
ImageMetrics texelMetrics(const TexelRadiance& test, const TexelRadiance& reference);
// The same over the texels where `only` is non-zero (one entry per texel), e.g. a chart's border.
ImageMetrics texelMetrics(const TexelRadiance& test, const TexelRadiance& reference,
                          const std::vector<std::uint8_t>& only);

// Per texel, 1 where a 4-neighbour is not a valid texel of the same chart (the chart's border,
// where a texel is partly covered and the surface's edge runs through it), else 0.
std::vector<std::uint8_t> chartBorder(const TexelMaps& maps);

// The sides as images, each width x (height * pages): layers "front" and "back" (EXR output).
std::vector<std::pair<std::string, Image>> texelImages(const TexelRadiance& radiance);

} // namespace bl::atlas
