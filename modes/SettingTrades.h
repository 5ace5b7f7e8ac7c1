// What a mode's settings trade on a given scene, said before rendering (issue 19 item 8).
//
// Four checks, each a criterion with a stated tolerance, evaluated on the host (Embree, no GPU);
// the first three from the points the camera sees (a coarse grid of primary rays):
//   shadow cube   the 4x4-PCF receiver-plane lookup of shaders/gpu/ShadowCubeLookup.glsl, replayed
//                 with rays along each tap's texel centre ray, against exact shadow rays: the
//                 relative error of the visible points' direct irradiance (shadowCubeError). The
//                 lookup's crease rule is not replayed: it changes only points within two texels of
//                 a crease on the outline of a room lit from outside (tests/core/gpu/
//                 ShadowCubeCreaseTest.cpp), where the filter alone leaks.
//   bundle pixel  the bundle query of shaders/bundle/Traversal.glsl, as the walks with hit payloads
//                 run it (multibounce, bidir, skylight: blBundleSurfaceNearestAcrossCreases): the
//                 fragments of the pixel's centre ray, up to 0.71 px beside x, each placed where
//                 x's own ray crosses its facet's plane, x's own triangle skipped; where that finds
//                 nothing, the near end's contact taps behind their gate (the rules of
//                 shaders/shared/BundleContacts.h, run by both; BundleRule::ListAlongFacetPlanes),
//                 replayed with rays, against exact rays from x: the relative error of the visible
//                 points' cosine-weighted visibility (ambient occlusion) over uniform directions
//                 (bundleVisibilityError). It predicts the images: a flat-shaded heightfield under
//                 a sky -4.49 / -1.08 / -0.23 % at 64 / 128 / 256^2, rendered -4.80 / -1.09 /
//                 -0.18 %; the flat-shaded bunny -16.6 / -3.8 % at 128 / 512^2, rendered -15.6 /
//                 -3.6 % (skylight). Depth maps (raster's environment maps, skylight's
//                 visibility = depth_map) replay bundle/DepthMapVisibility.glsl's centre instead:
//                 the one surface nearest the light, beyond both x's plane and its facet's
//                 (BundleRule::DepthMapNearestLight; its taps are not replayed). On the env-lit
//                 bunny at 512^2 that is -0.8 % (+- 0.2 %) (raster read 0.990 / 0.995 / 0.999 of
//                 the reference there, r / g / b). Neither replays smooth shading normals: their
//                 points sit on the facets (the bunny under a constant sky, smooth as in its file,
//                 read 0.953 in raster and 0.907 in skylight at 512^2, flat-shaded 0.992 / 0.964).
//   cut paths     a setting that ends paths early (multibounce's bundle_count <= 8): the share of
//                 the image the longer paths carry, from the reference path tracer at a small size
//                 with and without the cut (cutPathErrors).
// (Sharp glossy lobes need no check: their float evaluation, which lost 4% of a 1e6 lobe, is accurate
// to 1e-5 on the host, about 1e-4 on a GPU, since shaders/shared/CosinePower.h.)
// A check warns when its error exceeds kTradeTolerance by more than its own noise, and names the
// setting and the value that brings it under (or says none up to the largest it tries).
// A suggested fix is the first value tried (doubling) whose estimate lies within the tolerance.
// Checked against lavapipe renders (commands in the commit that added this): Sibenik, raster's
// direct light vs the reference at 96x64: -3.4 / -1.6 / -0.7 % at 512 / 1024 / 2048 texels, the
// shadow check -3.1 / -1.5 / -0.6 % (+- 0.6 / 0.3 / 0.1). Multibounce and bidir also reach the
// scene's other points along paths; the checks sample only what the camera sees.
// Drivers (render, the experiment runner, `bundlelab plan`) print settingTrades' lines once.
#pragma once

#include "modes/Mode.h" // TradeSettings, BundleRule

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bl {

struct Scene;
class EmbreeScene;

// The error a check tolerates before it warns: 1 % of the quantity it checks. The project's
// convergence tests judge image means at 1-2 % (tests/modes/*), the stress suite at 2 %: a trade
// below 1 % hides in their noise, one above it is what a user comparing against a reference
// would see first. Each check also needs its estimate to stand kTradeSigmas standard errors clear
// of the tolerance, so that its own sampling noise cannot raise a warning.
inline constexpr double kTradeTolerance = 0.01;
inline constexpr double kTradeSigmas = 3.0;

// Directions a long run of a bundle mode draws (skylight: one per iteration; 1024 is also the
// default of a stratified pass): a glossy lobe that one direction in more than this meets is said
// before rendering (directionsPerLobeHit).
inline constexpr double kLobeDirections = 1024.0;

// How many uniform bundle directions meet a Phong lobe of exponent e once, on average: e + 1; and
// a material's lobe (Ashikhmin-Shirley: sqrt((nu + 1)(nv + 1)) / 4). Derivation in the .cpp.
double directionsPerLobeHit(double exponent);
struct Material;
double directionsPerLobeHit(const Material& m);

// The visible points of the scene's camera (time 0): the first hits of a grid x grid set of
// primary rays through pixel centres of a grid at the camera's aspect.
struct ViewPoint {
    glm::vec3 position;
    glm::vec3 normal; // geometric, unit, toward the camera
    float offsetScale;
    std::uint32_t mesh;
    std::uint32_t triangle;
};
std::vector<ViewPoint> viewPoints(const EmbreeScene& rt, const Scene& scene, std::uint32_t grid);

// An estimate and its standard error.
struct TradeError {
    double error = 0.0; // relative: (approximation - exact) / exact
    double stderr_ = 0.0;
    bool exceeds() const; // |error| > kTradeTolerance + kTradeSigmas * stderr_: warn
    bool within() const;  // |error| <= kTradeTolerance: a setting suggested as the fix
};

// Relative error of the direct irradiance from light `light` (scene.lights[light], time 0) at the
// view points with a shadow cube of `resolution` texels a side, against exact shadow rays.
TradeError shadowCubeError(const EmbreeScene& rt, const std::vector<ViewPoint>& points,
                           std::uint32_t light, std::uint32_t resolution);

// Relative error of the cosine-weighted visibility of the view points over `directionsPerPoint`
// uniform directions each, answered by a bundle of `resolution` pixels a side (frame over the
// scene's bounding sphere, or fitted to the view points when `fitVisible`), against exact rays.
TradeError bundleVisibilityError(const EmbreeScene& rt, const std::vector<ViewPoint>& points,
                                 std::uint32_t resolution, bool fitVisible,
                                 std::uint32_t directionsPerPoint, BundleRule rule = BundleRule::ListAlongFacetPlanes);

// Relative error of the image mean (sum of every pixel's r + g + b) when paths end after each of
// `segments` segments, against paths of up to `uncut`: the reference path tracer at a small size
// (kCutPathWidth pixels wide, the camera's aspect), the same seed and samples for each cut so the
// difference holds the cut-off paths, not noise; stderr from the renders' variance of the mean.
inline constexpr int kCutPathWidth = 24;
inline constexpr std::uint32_t kCutPathSamples = 64;
std::vector<TradeError> cutPathErrors(const Scene& scene, const std::vector<std::uint32_t>& segments,
                                      std::uint32_t uncut = 64);

// The warning lines (empty: nothing to say) for `mode` on `scene`, with the fix for each.
std::vector<std::string> settingTrades(const Mode& mode, const Scene& scene);

} // namespace bl
