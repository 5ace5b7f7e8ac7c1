// The biases of mode atlas that its estimator tests allow, each derived from the method (not
// measured): tests/modes/atlas/AtlasModeTest.cpp holds the seeds' means to these bounds.
//
// 1. Interleaved transfer's missing bounces (AtlasMode.h). Direction j sends emission + the
//    estimate after j - 1 directions, and the estimate after n directions is the j^k-weighted mean
//    of what they received. The exchange is unbiased for a given sender and linear in it, so the
//    expected estimate holds the light of b reflections with the share
//        c(n, 0) = 1,  c(0, b) = 0 (b >= 1),  c(n, b) = sum_{j<=n} j^k c(j - 1, b - 1) / sum_{j<=n} j^k,
//    exactly (interleavedShares), where each direction is drawn independently of the ones before.
//    In the furnace (every texel emits 1, albedo 1/2) the expected texel is then
//    1 + sum_b c(n, b) / 2^b: 1.99876 at 128 directions, k = 2. A low-discrepancy sequence in its
//    own order (Halton, the default) places direction j by the directions before it, on which
//    the estimate it carries depends: furnaceGivenDirections (below) gives the expectation for
//    the directions a run took.
//
// 2. The texel average (texelBias). Each texel stands for the area average of its surface's
//    radiance; the exchange's estimate of it is unbiased (exact preimage areas A_T), and the view's
//    bilinear lookup between texel centres integrates to the same power inside a chart (the tent
//    functions' integrals are the texels' areas). So averaging only moves light within a texel,
//    and moving light by at most a texel side h changes the image only where
//    (a) the camera's weight per area (cos / d^2) or a receiver's kernel varies across the texel:
//        relative O(h / d) times the light's own relative change across the texel, O(h / d): second
//        order, (h / r)^2 with r the scene's bounding radius (0.05% for a 128^2 Cornell atlas);
//    (b) part of a texel is hidden: where another surface rests on it (a block on the floor, the
//        Cornell light 0.1 mm under the ceiling), the texels straddling that contact line average
//        the lit part with the covered part, so the visible part loses light to the hidden part,
//        first order in h. The hidden part of the straddling texels lies within h of the line, so
//        the power moved out of sight is at most h per unit of contact length times the radiance
//        there: in the image, at most L_near * Omega_strip, Omega_strip the solid angle of a strip
//        of width h along the contact lines as the camera sees it (visibility ignored)
//        and L_near the reference's brightest reflected radiance within a pixel of the strip.
//    The bound is (a) + (b) relative to the reference image's mean.
// What the bound leaves out (the tests say so where it matters): the shadow cubes' depth-bias band
// for point lights (the multibounce tests' kShadowTolerance, 1%), the view's 16 whole-frame sub-
// pixel offsets at the light's edge (experiments/atlas-results/discretization.md: the emitted
// layer, not the exchange).
#pragma once

#include "modes/Mode.h"
#include "scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace bl::test::atlas {

// c(n, b) for b = 0..maxReflections (above).
std::vector<double> interleavedShares(std::uint32_t directions, double k, int maxReflections);

// The relative deficit of the reference's reflected light (radiance - emitted) whose layers split
// by reflection count (direct 1, indirect1 2, indirect2 3, rest >= 4, each further reflection at
// most `albedo` of the one before: the transport's norm is at most the largest albedo), after n
// directions weighted j^k. `fromLights` = 1 where the direct layer comes from point lights (the
// direct atlas, a sender from the first direction on, like emission): reflection b then takes
// c(n, b - 1). `layers` (default all four) picks the layers the tested image holds.
// The least deficit puts all of `rest` at 4 reflections, the most spreads it geometrically.
struct Deficit {
    double least = 0.0, most = 0.0;
};
Deficit interleavedDeficit(const ImageSet& reference, std::uint32_t directions, double k, double albedo, int fromLights,
                           const std::vector<std::string>& layers = {"direct", "indirect1", "indirect2", "rest"});

// The texel side: the square root of the largest texel preimage area (a texel inside one triangle;
// the density is uniform over the scene, core/atlas).
double texelSide(const std::vector<float>& texelAreas);

// Contact lines: the geometric edges (borders, creases) of one mesh that lie within `gap` of
// another mesh's surface and at least `gap` from that mesh's own geometric edges (a block's bottom
// on the floor, a light under the ceiling; not the walls meeting at the box's creases).
struct ContactSample {
    glm::vec3 point, normal; // on the contact line; the covered surface's normal
    double length = 0.0;     // of contact line this sample stands for
};
std::vector<ContactSample> contactLines(const Scene& scene, double gap);

// The texel bias of the mean of `light` (the reference's image of the reflected light a test
// compares), relative, printed: (b) can only lose light, (a) goes either way.
struct TexelBias {
    double hidden = 0.0;      // (b): at most this share lost
    double secondOrder = 0.0; // (a): either way
};
// `bothSides`: the strip on the contact edge's own surface loses light too (skylight: a point's
// visibility is the ray through its bundle pixel's centre, up to h away, which for points within h
// of a contact may pass under the other surface), bounded with that surface's cosine toward the
// camera taken as 1.
TexelBias texelBias(const Scene& scene, const Image& light, double texelSide, bool bothSides = false);

// The furnace (data/analytic/furnace.toml: the cube [-1, 1]^3, every face emitting 1 inward,
// albedo `albedo`) after interleaved transfer over the given directions, in expectation over what
// else the mode draws (the bundle grid's sub-pixel shift and rotation): the area-weighted mean of
// the inner sides' radiance. Given the directions the exchange is linear in its sender and its
// grid placement is independent of the directions before, so this expectation is the recursion
// of interleavedShares run direction by direction with each direction's own transport, here
// integrated on a grid of `cells`^2 cells per face (`samples`^2 points each; a cell receives
// 2 albedo |cos| times the mean sender of where its points' rays along the inward one of +-omega
// leave the box). Averaged over directions drawn independently it is furnaceExpectation's
// closed form; over a low-discrepancy sequence in its own order it is not: direction j is placed
// where directions 1..j-1 left gaps, so it depends on the estimate it carries (the Halton
// shortfall of the interleaved furnace: 0.76 / n at 32 directions, 1.1 / n at 128, 1.3 / n at
// 512). In the cube, where light lands within a face hardly matters (one cell per face gives the
// same to 1e-6): the tests that use this check the recursion and its dependence on the
// directions, not the transport's geometry within a face.
double furnaceGivenDirections(const std::vector<glm::vec3>& directions, double k, double albedo, int cells,
                              int samples);

// The bracket [lower, upper] of the expected relative mean (1 = the reference) these biases
// allow, as the centre and half-width a tolerance test takes.
struct Bracket {
    double centre = 1.0, halfWidth = 0.0;
};
Bracket bracket(const Deficit& deficit, const TexelBias& texel, double other = 0.0);

} // namespace bl::test::atlas
