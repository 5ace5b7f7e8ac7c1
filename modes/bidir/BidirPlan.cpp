// Mode bidir's parameters and pass plan (what runs for a scene and why).
#include "modes/bidir/BidirMode.h"

#include "modes/EmitterPointParameters.h"
#include "modes/LightShadowPass.h"
#include "scene/Scene.h"

#include <string>

namespace bl {

std::vector<ParamSpec> BidirMode::parameters() {
    std::vector<ParamSpec> params{
        {kPairs, std::int64_t{21}, "pairs", "K VPL/bundle pairs per frame ([TO12] used 21)", 1, 4096, {}},
        {kStrategy, std::string("mis"), "",
         "one-bounce strategy: vpl (light paths), bundle (camera paths) or mis (both, balance heuristic)", 0, 0,
         {"vpl", "bundle", "mis"}},
        {kBundleResolution, std::int64_t{256}, "pixels", "side of each bundle ([TO12]: 256^2)", 16, 8192, {}},
        {kShadowResolution, std::int64_t{1024}, "texels", "face side of the lights' shadow cubes ([TO12]: 1024^2)",
         16, 8192, {}},
        {kVplShadowResolution, std::int64_t{256}, "texels", "face side of each VPL's shadow cube ([TO12]: 256^2)", 16,
         8192, {}},
        {kVplShadowTaps, std::int64_t{4}, "taps per side",
         "PCF taps a side of the VPL cubes' lookups (4: 4x4 like the lights'; fewer: faster, VPL shadows filtered "
         "differently)",
         1, 4, {}},
        {kDirections, std::string("random"), "", "bundle direction sequence", 0, 0, {"random", "halton"}},
        {kMemoryCap, std::int64_t{2048}, "MiB", "node storage limit of the bundle pool; a frame that needs more is refused",
         1, 1 << 20, {}},
        {kBounces, std::int64_t{2}, "", "indirect bounces: 1 (Eq. 3-6) or 2 (also Eq. 7-8, layer indirect2)", 1, 2, {}},
        {kSuppression, std::string("none"), "",
         "glossy artifact suppression ([TO12] section 5): none (unbiased), clamp (the lobe truncated at d/m) or "
         "roughness (its exponent lowered to that peak, Eq. 10-12)",
         0, 0, {"none", "clamp", "roughness"}},
        {kVplSource, std::string("rsm"), "",
         "VPLs from reflective shadow cubes on the GPU (rsm, [TO12] 4.1) or light rays traced on the CPU (traced)", 0, 0,
         {"rsm", "traced"}},
        {kRsmResolution, std::int64_t{256}, "texels", "face side of the reflective shadow cubes ([TO12]: 256^2)", 4,
         4096, {}},
        {kEnvironmentBundles, std::int64_t{21}, "bundles",
         "bundles per frame for direct environment light (Eq. 2 importance directions; none without an environment)",
         0, 4096, {}},
        {kSuppressionNeighbours, 16.0, "samples", "m' of the suppression's neighbour count m = m' f cos / D ([TO12]: 16)",
         1e-3, 1e6, {}},
        {kInterleave, std::int64_t{1}, "sub-images per side",
         "spatial interleaving: n x n sub-images, each with every n^2-th pair, gathered and blurred ([TO12s] A.1; 1: off)",
         1, 16, {}},
        {kInterleaveFilter, std::string("on"), "", "geometry-aware blur of the gathered indirect light", 0, 0,
         {"on", "off"}},
        {kTemporal, std::string("off"), "",
         "temporal interleaving: 2x2 sub-pixel caches, round-robin, reverse reprojection ([TO12s] A.2)", 0, 0,
         {"on", "off"}},
        {kReprojection, std::string("auto"), "",
         "temporal caches: auto warps into the caches' cameras only for an animated camera; always warps", 0, 0,
         {"auto", "always"}},
        {kTemporalDepthVariance, 1e-4, "log-depth^2",
         "2 sigma^2 of the temporal caches' log-depth Gaussian h = exp(-log^2(z/z_c) / (2 sigma^2)) ([TO12s]: 1e-4)",
         1e-8, 1e4, {}},
        {kFit, std::string("visible"), "",
         "bundle frames around the camera-visible points of the frame ([TO12s] B.1) or the scene's bounding sphere", 0,
         0, {"visible", "scene"}},
        {kTwoBounceClamp, 0.0, "scene radius",
         "two-bounce term only: |x1 - x2| taken as at least this fraction of the scene's bounding radius (0: off, "
         "unbiased)",
         0.0, 1.0, {}},
    };
    return withEmitterPointParameters(std::move(params), "frame",
                                      "direct, one- and two-bounce light from area emitters (0: area lights left out)", 0);
}

// The pass ids iterate() and setScene() ask about are the kBidirPass* names in BidirMode.h.
PassPlan BidirMode::plan(const Scene& scene) const {
    const SceneFeatures f = scene.features();
    const BidirOptions& o = mOptions;
    const std::string& strategy = o.strategyName;
    const auto pairs = std::to_string(o.pairs);
    const bool lights = f.shadowCastingLights() > 0;
    const bool twoBounce = o.twoBounce();
    const bool vplStrategy = strategy == "vpl";
    const bool bundleStrategy = strategy == "bundle";
    PassPlan p;
    p.add("gbuffer", "gbuffer", true, "always", std::to_string(f.triangles) + " triangles, jittered every frame");
    p.add(lightShadowCubesPass(f, "", "frame"));
    const bool area = f.emissiveMeshes && o.emitterPoints > 0;
    // Area emitters start light paths as one more source (VplSampler.h; with vpl_source = rsm the
    // pairs that draw it are traced on the host).
    const bool areaVpls = area;
    const bool sources = lights || areaVpls;
    const bool vpl = sources && (!bundleStrategy || twoBounce);
    p.add(kBidirPassVpls, "VPL rays + VPL shadow cubes", vpl,
          !sources ? "no-point-or-spot-lights" : !vpl ? "strategy-bundle-one-bounce" : o.rsmVpls && lights ? "rsm" : "traced",
          !sources ? "no point, spot or area light to start light paths"
          : vpl   ? pairs + " VPLs per frame (" +
                      (!lights     ? std::string("area emitters only: CPU rays, Embree")
                       : o.rsmVpls ? "GPU, " + std::to_string(o.rsmResolution) + "^2 reflective shadow cube per light"
                                   : std::string("CPU rays, Embree")) +
                      (areaVpls && lights ? ", the area emitters one more source (CPU rays)" : "") +
                      "), a " + std::to_string(o.vplShadowResolution) + "^2 cube each" +
                      (bundleStrategy ? " (for the two-bounce term only)" : "")
                  : "strategy = bundle with bounces = 1 uses no VPL");
    p.add(kBidirPassAreaVpls, "VPLs from area emitters", vpl && areaVpls,
          !area ? "no-area-emitters" : !vpl ? "strategy-bundle-one-bounce" : "traced",
          !area  ? "no area emitter (or emitter_points = 0)"
          : !vpl ? "strategy = bundle with bounces = 1 uses no VPL"
                 : "x0 on the emitters by power, a cosine-weighted CPU ray: one source among the lights, MIS "
                   "against the emitter points at the bundles' hits");
    // Bundles for the bundle strategy and the two-bounce term; area emitters without VPLs: for the
    // bundle strategy's one-bounce term.
    const bool bundles = (sources && (!vplStrategy || twoBounce)) || (area && !vplStrategy);
    p.add(kBidirPassBundles, "bundle builds", bundles,
          !lights && !area ? "no-lights"
          : !bundles       ? (sources ? "strategy-vpl-one-bounce" : "strategy-vpl-area-only")
          : vplStrategy    ? "two-bounce-term"
                           : "camera-paths",
          !lights && !area ? "no point, spot or area light: nothing for camera paths to reach"
          : !bundles && !sources ? "strategy = vpl: area emitters' one-bounce light needs the bundles"
          : bundles ? pairs + " bundles of " + std::to_string(o.bundleResolution) +
                          "^2 with hit payload per frame, around the " +
                          (o.fitVisible ? "visible points" : "scene's sphere") +
                          (vplStrategy ? " (for the two-bounce term only)" : "")
                    : "strategy = vpl with bounces = 1 uses no bundle");
    p.add("evaluate", "evaluate", true,
          lights ? "lights" : area ? "area-emitters-only" : f.environment && o.environmentBundles > 0 ? "environment-only" : "emitters-only",
          lights ? "direct + one-bounce (" + strategy + ")" + (twoBounce ? " + two-bounce" : "") + " at every visible point"
          : area ? (areaVpls ? "area emitters' direct + one-bounce (" + strategy + ")" + (twoBounce ? " + two-bounce" : "")
                    : vplStrategy ? "no point/spot light: area emitters' direct light"
                                  : "no point/spot light: area emitters' direct and one-bounce light")
          : f.environment && o.environmentBundles > 0
              ? "no point/spot light: emitters, environment background and direct environment light by bundles"
              : "no point/spot light: emitters and environment background only");
    const std::string& suppression = o.suppressionName;
    const bool suppress = o.suppressesGlossy(f);
    p.add(kBidirPassSuppression, "glossy suppression (" + suppression + ")", suppress,
          suppress ? "glossy-vertices" : suppression == "none" ? "suppression-none" : !sources ? "no-point-or-spot-lights" : "no-glossy-material",
          suppress               ? "sample densities (Eq. 13-17) at the glossy vertices of indirect paths"
          : suppression == "none" ? "suppression = none"
          : !sources             ? "no indirect light without point/spot lights or area emitters"
                                 : "no glossy material: every BRDF is Lambertian, nothing to suppress");
    const std::uint32_t n = o.interleave;
    const bool filter = o.interleaveFilter;
    p.add(kBidirPassInterleave, "split + gather (interleave " + std::to_string(n) + ")", n > 1,
          n > 1 ? "interleave-on" : "interleave-1",
          n > 1 ? std::to_string(n * n) + " sub-images (pixels " + std::to_string(n) + " apart in x and y), " +
                      std::to_string(o.pairs / (n * n)) + "+ pairs each"
                : "interleave = 1");
    p.add("interleave-filter", "geometry-aware filter", n > 1 && filter,
          n == 1 ? "interleave-1" : filter ? "filter-on" : "filter-off",
          n == 1   ? "interleave = 1: nothing to recombine"
          : filter ? std::to_string(n) + "x" + std::to_string(n) + " neighbourhood, normal and depth weights"
                   : "interleave_filter = off");
    const bool temporal = o.temporal;
    p.add("temporal-caches", "temporal caches", temporal, temporal ? "temporal-on" : "temporal-off",
          temporal ? "4 sub-pixel caches, one rewritten per frame" : "temporal = off");
    const bool reproject = temporal && (scene.camera.animated() || o.reprojectAlways);
    p.add(kBidirPassReprojection, "reverse reprojection", reproject,
          !temporal ? "temporal-off" : !reproject ? "static-camera" : scene.camera.animated() ? "animated-camera" : "reprojection-always",
          !temporal  ? "temporal = off"
          : reproject ? (scene.camera.animated() ? "the camera is animated: each cache warped into its camera"
                                                  : "reprojection = always")
                      : "static camera: every cache's warp is the identity (moving meshes still fail the "
                        "log-depth test), the image is the same");
    const std::uint32_t envBundles = o.environmentBundles;
    p.add(kBidirPassEnvironment, "environment bundles", f.environment && envBundles > 0,
          !f.environment ? "no-environment" : envBundles > 0 ? "importance-directions" : "environment-bundles-0",
          !f.environment   ? "no environment"
          : envBundles > 0 ? std::to_string(envBundles) + " bundles per frame by Eq. 2 importance: direct "
                                                          "environment light (indirect: not yet)"
                           : "environment_bundles = 0: the environment lights nothing",
          f.environment && envBundles == 0);
    if (f.emissiveMeshes && !area) {
        p.add(kBidirPassEmitterPoints, "area light", false, "emitter-points-0", "emitter_points = 0 leaves the area emitters out",
              true);
    } else {
        p.add(kBidirPassEmitterPoints, "emitter points", area, area ? "area-emitters" : "no-area-emitters",
              area ? std::to_string(o.emitterPoints) + " point(s) on the area emitters per frame, by power, x 6 faces of " +
                         std::to_string(o.emitterShadowResolution) +
                         "^2: their direct light, and their one-bounce light at the bundles' hits (with the area "
                         "VPLs by MIS)"
                   : "no emissive mesh");
    }
    return p;
}

} // namespace bl
