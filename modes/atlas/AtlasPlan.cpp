// Mode atlas's parameters and pass plan (what runs for a scene and why).
#include "modes/atlas/AtlasMode.h"

#include "modes/EmitterPointParameters.h"
#include "modes/EnvironmentShadowParameters.h"
#include "scene/Scene.h"

namespace bl {

std::vector<ParamSpec> AtlasMode::parameters() {
    std::vector<ParamSpec> params{
        {kAtlasResolution, std::int64_t{512}, "texels",
         "side of an atlas page; the texel density follows from the scene's surface area", 16, 16384, {}},
        {kBundleResolution, std::int64_t{512}, "pixels", "side of each direction's bundle (frame over the bounding sphere)",
         8, 8192, {}},
        {kDirections, std::string("halton"), "",
         "global directions: uniform on the sphere (Hermes et al.: Halton), or importance = environment luminance + "
         "offset ([TO12] Eq. 2; every direction is weighted by its density)",
         0, 0, {"halton", "random", "stratified", "importance"}},
        {kStrata, std::int64_t{1024}, "directions", "directions per pass of the stratified sequence", 1, 1 << 24, {}},
        {kImportanceOffset, 1.0, "",
         "L_o of directions=importance as a fraction of the mean environment luminance: keeps every direction sampled "
         "for the exchange between surfaces",
         0.0, 1e6, {}},
        {kWeighting, 2.0, "",
         "k: direction j weighs j^k in the estimate, forgetting the first directions' missing bounces (0: plain mean)",
         0.0, 8.0, {}},
        {kTransfer, std::string("interleaved"), "",
         "interleaved: the sender is rewritten after every direction (Hermes et al.'s default); bounce: one pass of "
         "bounce_directions per bounce, each sending the previous pass's light",
         0, 0, {"interleaved", "bounce"}},
        {kBounceDirections, std::int64_t{256}, "directions", "transfer = bounce: directions per pass (bounce)", 1, 1 << 24,
         {}},
        {kMaxSegments, std::int64_t{0}, "segments",
         "transfer = bounce: longest path kept (1 = emitters only, 2 = one reflection, ...; 0: no limit); the last "
         "pass keeps refining",
         0, 1 << 16, {}},
        {kViewSamples, std::int64_t{16}, "samples", "jittered camera samples per pixel when the atlas is viewed (resolve)",
         1, 4096, {}},
        {kBilinear, true, "", "bilinear lookups between texel centres inside a chart (else the texel alone)", 0, 0, {}},
        {kShadowResolution, std::int64_t{512}, "texels", "side of each shadow cube face (point and spot lights)", 16, 8192,
         {}},
        {kLightSamples, std::int64_t{2}, "per side",
         "n: an n x n grid of sample points per texel averages point/spot light over the texel's surface", 1, 16, {}},
        {kGlossy, std::string("transfer"), "",
         "glossy lobes: transfer = glossy transfer atlas + final gather toward the eye ([HHGM10] 5.3-5.4); gather = "
         "toward the eye only (no glossy bounce between surfaces); off = their albedo only (diffuse)",
         0, 0, {"transfer", "gather", "off"}},
        {kDelayIndirect, std::int64_t{0}, "directions",
         "N: the first N directions carry direct light only (emitters send, reflected light does not), indirect light "
         "from direction N + 1 on ([HHGM10] 6.4); the one-bounce (plain mean: its sender is fixed) and multi-bounce "
         "(j^k from its first direction) estimates are summed apart (0: one estimate; interleaved transfer only)",
         0, 1 << 24, {}},
        {kFirstShot, std::string("auto"), "",
         "the area emitters' and the environment's direct light into the direct atlas every direction (radiosity's "
         "first shot: emitter points, gpu/EmitterPointPass.h, and environment_shots directional shadow maps), the "
         "exchange then carrying reflected light only; it needs interleaved transfer, no delay_indirect and no glossy "
         "transport: auto = on where those hold, on = refuse settings that break them",
         0, 0, {"auto", "on", "off"}},
        {kShotSamples, std::string("one"), "",
         "the first shot's sample points per texel and direction: one = one of the light_samples grid drawn by its "
         "area (a golden-ratio rotation per texel over the directions; unbiased, and light_samples^2 times fewer shadow "
         "reads where the emitter points' own noise dominates), all = the whole grid",
         0, 0, {"one", "all"}},
        {kMemoryCap, std::int64_t{0}, "MiB",
         "node storage limit of the bundle pool (0: half the largest device-local heap); a direction that needs more is "
         "refused",
         0, 1 << 20, {}},
        {kPoolNodes, std::int64_t{4}, "nodes",
         "the bundle pool's first size, per bundle pixel (at most what memory_cap_mib or the device allows); a "
         "direction whose bundle needs more grows it (counted in bundle_rebuilds): a deep scene starts larger to "
         "skip the first rebuilds",
         1, 1 << 16, {}},
    };
    params = withEmitterPointParameters(std::move(params), "direction",
                                        "the first shot (first_shot), the area emitters' direct light", 1);
    return withEnvironmentShadowParameters(
        std::move(params), "direction",
        "the first shot (first_shot), the environment's direct light at the texels' sample points (shot_samples); "
        "0: the exchange's list ends carry the environment");
}

PassPlan AtlasMode::plan(const Scene& scene) const {
    const SceneFeatures f = scene.features();
    const AtlasModeOptions& o = mOptions;
    const auto r = std::to_string(o.bundleResolution);
    const auto a = std::to_string(o.atlasResolution);
    PassPlan p;
    p.add("atlas", "atlas", true, "always",
          a + "^2 texels per page over " + std::to_string(f.triangles) +
              " triangles, built once at set-up (charts, packing, exact texel areas)");
    p.add("bundles", "bundle build", true, "always",
          "one " + r + "^2 bundle per direction with hit payload (triangle, barycentrics)");
    p.add("bundle-sort", "bundle sort", true, "always", "depth order: consecutive hits of a list see each other");
    const FirstShotChoice choice = firstShotChoice(scene);
    const bool shot = choice.runs;
    std::string shotWhat;
    if (choice.area) {
        shotWhat = std::to_string(o.emitterPoints) + " emitter point(s) per direction, a " +
                   std::to_string(o.emitterShadowResolution) + "^2 cube each";
    }
    if (choice.environment) {
        shotWhat += (shotWhat.empty() ? "" : "; ") + std::to_string(o.environmentShots) +
                    " environment direction(s) per direction by its importance, a " +
                    std::to_string(o.environmentShadowResolution) + "^2 depth map each";
    }
    p.add(kPassFirstShot, "first shot", shot, choice.code,
          shot ? shotWhat + (o.shotAllSamples ? ": their light averaged over each texel's sample points"
                                              : ": their light at one sample point per texel, drawn by its area,") +
                     " into the direct atlas"
               : choice.why);
    std::string exchange = shot ? "consecutive hits exchange reflected radiance both ways (sender = direct + mean)"
                                : "consecutive hits exchange radiance both ways (interleaved: sender = emission + mean)";
    exchange += !f.emissiveMeshes ? "; no emissive meshes"
                : shot            ? "; the emitters' light was shot (first shot), they send what they reflect"
                                  : "; emitters are the source";
    exchange += !f.environment        ? "; no environment: list ends receive nothing"
                : choice.environment ? "; the environment's light was shot: list ends receive nothing"
                                     : "; environment at list ends";
    p.add("exchange", "exchange", true, o.bounce ? "transfer-bounce" : "transfer-interleaved", exchange);
    p.add("update", "update", true, "always",
          "received radiance into compensated sums, only for the texel sides the direction touched (a list the "
          "exchange appends to); the sender is formed where it is read");
    const std::uint32_t delay = o.delayIndirect;
    p.add(kPassDelayedIndirect, "delayed indirect", delay > 0, delay > 0 ? "delay-indirect" : "delay-indirect-0",
          delay > 0 ? "directions 1-" + std::to_string(delay) +
                          ": emitters send, reflected light does not; one-bounce (layer direct) and multi-bounce "
                          "(layer rest) estimates summed apart"
                    : "delay_indirect = 0: one estimate");
    const bool lights = f.shadowCastingLights() > 0;
    const auto n = std::to_string(o.lightSamples);
    p.add("light-shadow-cubes", "shadow maps", lights, lights ? "once-at-set-up" : "no-point-or-spot-lights",
          lights ? std::to_string(f.shadowCastingLights()) + " point/spot light(s): one " +
                       std::to_string(o.shadowResolution) + "^2 cube each, once; their light averaged over " + n + "x" +
                       n + " points per texel into a direct atlas (layer direct), the exchange's first sender"
                 : "no point or spot lights");
    const std::string& glossy = o.glossy;
    const bool glossyOn = f.glossy && glossy != "off" && !o.bounce;
    const std::string off = !f.glossy ? "no-glossy-material" : glossy == "off" ? "glossy-off" : "transfer-bounce";
    const std::string why = glossy == "off" ? "glossy = off" : "transfer = bounce (a pass's sender is fixed)";
    const bool transfer = glossyOn && glossy == "transfer";
    p.add(kPassGlossyTransfer, "glossy transfer", transfer,
          transfer ? "glossy-transfer" : glossyOn ? "glossy-gather" : off,
          !f.glossy  ? "no glossy materials"
          : !glossyOn ? why + ": the lobes are NOT transported (their albedo only)"
          : transfer  ? std::string("glossy texels store what their lobe reflects toward the next direction (in the "
                                    "receiver), the next direction sends it") +
                            (lights ? "; point/spot lights' lobes per texel sample too" : "")
                      : "glossy = gather: no glossy bounce between surfaces");
    p.add(kPassGlossyGather, "glossy gather", glossyOn, glossyOn ? "glossy-" + glossy : off,
          !f.glossy  ? "no glossy materials"
          : !glossyOn ? why + ": no glossy reflection toward the eye"
                      : std::string("per direction a jittered camera G-buffer; each glossy pixel's bundle neighbour "
                                    "sends through the lobe toward the eye") +
                            (lights ? "; point/spot lights' highlight per view sample" : ""));
    p.add("view", "view", true, "always",
          std::to_string(o.viewSamples) +
              " jittered camera samples per pixel of the atlas at resolve (G-buffer + atlas uv raster)");
    return p;
}

} // namespace bl
