// Mode atlas against closed forms and the CPU reference path tracer (never against itself).
//
// Statistics (tests/support/Statistics.h, as in MultibounceTest.cpp): the estimator tests render
// kSeeds independent seeds and hold the seeds' mean to the closed form or the reference within a
// tolerance plus t(1 - alpha/2, n - 1) standard errors, behind the noise gate stderr <= tol / 3.
// The expected value carries the interleaved transfer's missing bounces, computed exactly, and the
// tolerance is the texel average's bias bound, both derived in AtlasBias.h; where the method has
// no bias (the furnace: constant radiance, exact texel areas, AtlasFurnaceTest.cpp) the tolerance
// is the resolution the seeds afford, centred on the closed form.
#include "modes/atlas/AtlasTestFixture.h"

#include "base/Error.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "support/AnalyticScenes.h"

#include <algorithm>
#include <cmath>

using namespace bl;
using namespace bl::test::atlasmode;

namespace {
// Direct light from point lights (shadow cubes, 4x4 PCF): the filter is symmetric about a shadow
// boundary, so it moves no light to first order; the depth bias's band beside contact shadows is
// two texels of a 512^2 face (under 2 mm at the box's distances), held to 1% as in the multibounce
// tests (kShadowTolerance there).
constexpr double kShadowTolerance = 0.01;
// The emitter points' cubes (first shot; 256^2, one tap): a receiver within half a texel (2 mm at
// the box's far corners) of a concave contact may read the other surface; those bands are about
// 0.9 % of the box's surface and lose at most half their light there: under 0.5 %, held to 1 %
// (tests/modes/multibounce/MultibounceTest.cpp: kEmitterShadowTolerance, the same bound).
constexpr double kEmitterShadowTolerance = 0.01;
// The largest albedo of the Cornell boxes' materials (the light's 0.78): the transport's norm.
constexpr double kCornellAlbedo = 0.78;
// The blocks scenes' (ao-blocks, sky-blocks) largest albedo, the white block's, with the glossy
// lobe removed.
constexpr double kBlocksAlbedo = 0.725;

} // namespace

// Settings that would mix path lengths are refused before any work, with the value named:
// delay_indirect with bounce-by-bounce transfer, max_segments with interleaved transfer.
TEST_F(Atlas, RefusesSettingsThatMixPathLengths) {
    const Scene s = loadSmall("data/analytic/furnace.toml", 16);
    const auto refusal = [&](const std::vector<std::string>& settings) -> std::string {
        std::unique_ptr<Mode> mode = createMode("atlas", settings);
        try {
            mode->setScene(s, &ctx());
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(refusal({"transfer=bounce", "delay_indirect=4"}).find("delay_indirect = 4"), std::string::npos);
    EXPECT_NE(refusal({"transfer=interleaved", "max_segments=2"}).find("max_segments"), std::string::npos);
    EXPECT_EQ(refusal({"transfer=bounce", "max_segments=2", "atlas_resolution=48", "bundle_resolution=64"}), "");
}


// The Cornell box with its area light against the reference path tracer: the reflected light
// (radiance - emitted: the emitted layer is the view's sampling of the light, not the exchange) of
// kSeeds seeds at 128 directions, 128^2 atlas and bundles (the bundle pixel, 15 mm, about the
// texel, 13 mm: finer bundles only add texel sampling noise), against the reference's less the
// interleaved deficit, within the texel bias (AtlasBias.h: the blocks' footprints on the floor
// and the light's outline under the ceiling, 1.9 m of contact line: 1.6%, second order 0.08%):
// the bracket [0.977, 1.001] of the reference. 512 directions per seed: at 128 the seeds' mean
// was 0.960 of the reference, below the derived deficit (at most 1.5% there) by more than its
// noise (0.4%): presumably the Halton order's shortfall the furnace shows (AtlasFurnaceTest.cpp:
// FollowsTheDirectionSequence); not verified (directions=random at 128: 0.0603 +- 0.0032 of
// 0.0632, 8 seeds, too noisy to tell). 8 seeds at 512: 0.9878 +- 0.0037 (the
// noise gate's margin is small: stderr 0.00024 against tol / 3 = 0.00025).
// A wrong hemisphere density or texel area moves the mean by 2x, a missing bounce by ~20%; the
// exchange's received light x 1.10: +21.5% (fails).
TEST_F(Atlas, CornellMatchesReference) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", kStatResolution);
    expectReflectedLight(s, 512, {"atlas_resolution=128", "bundle_resolution=128", "view_samples=16", "first_shot=off"},
                         kSeeds, kCornellAlbedo, 0, "cornell");
}

// A constant white sky over blocks (data/analytic/ao-blocks.toml): light enters only where a list
// ends (the ray leaves the scene). The mode is diffuse only, so the glossy block's lobe is removed for
// both renderers. The reflected light (radiance - emitted: the emitted layer is the sky seen
// directly) of 4 seeds against the reference's, less the interleaved deficit, within the texel bias
// (AtlasBias.h): the sky reaches every texel from the first direction on, as point lights do
// (fromLights = 1), the blocks' footprints on the floor are the contact lines, and the transport's
// norm is at most the largest albedo, the white block's 0.725. 1024 directions: a seed's Halton set
// can be ~1% off at 256 (seed 1: -0.9% against seeds 2-4) while seeds agree to 0.1% at 1024, and
// the Halton order's own shortfall (AtlasFurnaceExpectation.FollowsTheDirectionSequence, about 1 / n
// of the interreflected part) is then far inside the bracket. Same cost as the one seed of 512
// directions at 256^2 this replaced. Mutation: received light x 1.10 (fails).
TEST_F(Atlas, EnvironmentAtListEndsMatchesReference) {
    Scene s = loadSmall("data/analytic/ao-blocks.toml", kStatResolution);
    for (Material& m : s.materials) m.specular = glm::vec3(0.0f);
    expectReflectedLight(s, 1024, {"atlas_resolution=128", "bundle_resolution=128", "view_samples=16", "environment_shots=0"},
                         4, kBlocksAlbedo, 1, "sky");
}

namespace {

// The sum of an image set's layers `names`.
Image sumOf(const ImageSet& set, const std::vector<std::string>& names) {
    Image out = bl::test::layerOf(set, names.front());
    for (std::size_t i = 1; i < names.size(); ++i) {
        const Image& more = bl::test::layerOf(set, names[i]);
        for (std::size_t p = 0; p < out.pixelCount(); ++p) out.pixels()[p] += more.pixels()[p];
    }
    return out;
}

} // namespace

void Atlas::expectReflectedLight(const Scene& s, std::uint32_t directions, const std::vector<std::string>& settings,
                                 std::uint32_t seeds, double norm, int fromLights, const std::string& label) {
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    const Image reflected = reflectedLight(reference);
    double side = 0.0;
    const std::vector<double> means = reflectedMeans(s, directions, settings, seeds, side);
    const bias::Deficit deficit = bias::interleavedDeficit(reference, directions, kWeighting, norm, fromLights);
    const bias::Bracket b = bias::bracket(deficit, bias::texelBias(s, reflected, side));
    std::printf("%s: interleaved deficit %.5f to %.5f: expected %.4f +- %.4f of the reference\n", label.c_str(),
                deficit.least, deficit.most, b.centre, b.halfWidth);
    expectSeedsAgree(means, b.centre * lumaMean(reflected), b.halfWidth * lumaMean(reflected), label + " reflected light");
}

void Atlas::expectDirectAndIndirect(const Scene& s, std::uint32_t directions, const std::vector<std::string>& settings,
                                    std::uint32_t seeds, double norm, double other, const std::string& label,
                                    double mapStrip) {
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    const Image& referenceDirect = bl::test::layerOf(reference, "direct");
    const Image referenceIndirect = sumOf(reference, {"indirect1", "indirect2", "rest"});
    std::vector<double> direct, indirect;
    double side = 0.0;
    for (std::uint32_t seed : stats::seeds(seeds)) {
        const ImageSet out = resolveSeed(s, directions, settings, seed, side);
        direct.push_back(lumaMean(bl::test::layerOf(out, "direct")));
        indirect.push_back(lumaMean(bl::test::layerOf(out, "rest")));
    }
    const bias::TexelBias directBias = bias::texelBias(s, referenceDirect, side);
    double strip = 0.0; // the depth maps' contact strips, either way
    if (mapStrip > 0.0) {
        const bias::TexelBias b = bias::texelBias(s, referenceDirect, mapStrip, true);
        strip = b.hidden + b.secondOrder;
        std::printf("%s: the depth maps' contact strips (%.4f wide) move at most %.5f of the direct light\n",
                    label.c_str(), mapStrip, strip);
    }
    const bias::Bracket d = bias::bracket({}, directBias, other + strip);
    expectSeedsAgree(direct, d.centre * lumaMean(referenceDirect), d.halfWidth * lumaMean(referenceDirect),
                     label + " direct");
    const bias::Deficit deficit =
        bias::interleavedDeficit(reference, directions, kWeighting, norm, 1, {"indirect1", "indirect2", "rest"});
    const bias::Bracket i = bias::bracket(deficit, bias::texelBias(s, referenceIndirect, side), other + strip);
    std::printf("%s: transport norm %.3f, interleaved deficit of the indirect light %.5f to %.5f: expected %.4f +- "
                "%.4f\n",
                label.c_str(), norm, deficit.least, deficit.most, i.centre, i.halfWidth);
    expectSeedsAgree(indirect, i.centre * lumaMean(referenceIndirect), i.halfWidth * lumaMean(referenceIndirect),
                     label + " indirect");
}

// The Cornell box lit by a point light only ([HHGM10] section 6.5 hybrid): its light reaches the
// atlas by cube shadow maps averaged over 2x2 points per texel (layer `direct`), the exchange carries
// it on (layer `rest`). kSeeds seeds at 64 directions, 128^2 atlas and bundles, against the
// reference's layers: `direct` within kShadowTolerance + the texel bias of the direct light (the
// blocks' footprints: texels straddling them average the lit floor with the covered part), `rest`
// against the reference's indirect1 + indirect2 + rest less the interleaved deficit (the direct
// atlas sends from the first direction on, like emission) within the shadow tolerance + the texel
// bias of the indirect light. 8 seeds: direct 1.0017 of the reference (the shadow cubes and the
// texels' sample points take no seed; only the view's pixel jitter does), indirect 0.974 +- 0.008 (bracket 0.943 to
// 1.011). Mutations: the direct pass x 1.10: direct +10.2%, indirect +9.7% (both fail); the
// exchange's received light x 1.10: indirect +20% (fails).
TEST_F(Atlas, CornellPointLightMatchesReference) {
    Scene s = loadSmall("data/cornell-box/cornell-point.toml", kStatResolution);
    expectDirectAndIndirect(s, 64, {"atlas_resolution=128", "bundle_resolution=128", "view_samples=4", "shadow_resolution=512"},
                            kSeeds, kCornellAlbedo, kShadowTolerance, "cornell point");
}

// The area-lit Cornell box by the first shot (first_shot = on): the emitters' direct light by
// emitter points into the direct atlas (layer `direct`, a new set of 16 points every direction), the
// exchange carrying reflected light only (layer `rest`): the point-lit test above with the area
// light. `direct` within the points' cube bound (kEmitterShadowTolerance) + the texel bias of the
// direct light; `rest` against the reference's indirect layers less the interleaved deficit (the
// direct atlas sends from the first direction on, as there) within the same + the texel bias of the
// indirect light. Without the shot (the emission sent) the direct light would land in `rest`.
// 8 seeds: direct +0.51% (tolerance 1.77%), indirect -0.79% (4.11%). Mutation: the senders' constant
// part accumulated instead of set (the shot sent again every direction): indirect x 41 (fails).
TEST_F(Atlas, CornellFirstShotMatchesReference) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", kStatResolution);
    expectDirectAndIndirect(s, 64, {"atlas_resolution=128", "bundle_resolution=128", "view_samples=4", "first_shot=on"},
                            kSeeds, kCornellAlbedo, kEmitterShadowTolerance, "cornell first shot");
}

// The first shot is refused where its light would not reach every sender (a fixed pass sender,
// the one-bounce channel, the glossy transfer atlas), with the settings that allow it.
TEST_F(Atlas, FirstShotRefusesTransfersItDoesNotFeed) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", 16);
    Scene glossy = s; // a glossy material (on no mesh) turns the glossy transfer on
    Material lobe;
    lobe.name = "glossy";
    lobe.specular = glm::vec3(0.5f);
    lobe.exponentU = lobe.exponentV = 40.0f;
    glossy.materials.push_back(lobe);
    for (const auto& [scene, settings] :
         {std::pair{&s, std::vector<std::string>{"first_shot=on", "transfer=bounce"}},
          std::pair{&s, std::vector<std::string>{"first_shot=on", "delay_indirect=4"}},
          std::pair{&glossy, std::vector<std::string>{"first_shot=on", "glossy=transfer"}}}) {
        std::unique_ptr<Mode> mode = createMode("atlas", settings);
        try {
            mode->setScene(*scene, &ctx());
            ADD_FAILURE() << "accepted " << settings[1];
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("first_shot = on needs transfer=interleaved"), std::string::npos) << e.what();
        }
    }
    EXPECT_NO_THROW(createMode("atlas", {"first_shot=on", "glossy=off"})->setScene(glossy, &ctx()));
    // first_shot = auto (the default) leaves the shot out there and says why; on the plain box it runs.
    const auto firstShot = [&](const std::vector<std::string>& settings) {
        return createMode("atlas", settings)->plan(s).pass("first-shot");
    };
    const PlannedPass bounce = firstShot({"transfer=bounce"});
    EXPECT_FALSE(bounce.runs);
    EXPECT_EQ(bounce.code, "transfer-bounce") << bounce.reason;
    EXPECT_NO_THROW(createMode("atlas", {"transfer=bounce"})->setScene(s, &ctx()));
    EXPECT_TRUE(firstShot({}).runs);
    EXPECT_EQ(firstShot({"first_shot=off"}).code, "first-shot-off");
}

void Atlas::expectDirectLayersAdd(const Scene& one, const Scene& other, const Scene& both,
                                  const std::vector<std::string>& settings, const char* label) {
    const auto directMean = [&](const Scene& s) {
        const ImageSet out = run(s, 4, settings)->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        return lumaMean(bl::test::layerOf(out, "direct"));
    };
    const double a = directMean(one), b = directMean(other), ab = directMean(both);
    std::printf("direct: %s: %.6g + %.6g = %.6g, both %.6g\n", label, a, b, a + b, ab);
    EXPECT_GT(a, 0.1 * b);
    EXPECT_GT(b, 0.1 * a);
    EXPECT_NEAR(ab, a + b, 1e-4 * (a + b));
}

// A scene lit by both an area emitter and a point light: the first shot's light adds to the point
// light's in the direct atlas (the shot writes only the area part), and a point-lit scene without
// emitters takes first_shot with a transfer the shot could not feed (there is no shot). Same seed
// on every side, so the emitter points, the directions and the shadow cubes are the same and the
// direct layers add up to float rounding. Mutations: the shot overwriting the point lights' part
// (both = area only), a descriptor pool one storage image short (the set of the both-lit scene
// fails to allocate).
TEST_F(Atlas, FirstShotAddsToPointLights) {
    const bl::test::AreaAndPointLit lit =
        bl::test::areaAndPointLit(loadSmall("data/cornell-box/cornell.toml", 16), {278.0f, 400.0f, 279.5f});
    const Scene &areaOnly = lit.area, &pointOnly = lit.pointOnly, &both = lit.both;
    expectDirectLayersAdd(areaOnly, pointOnly, both,
                          {"atlas_resolution=32", "bundle_resolution=32", "first_shot=on"}, "area + point");
    std::unique_ptr<Mode> bounce = createMode("atlas", {"first_shot=on", "transfer=bounce"});
    EXPECT_NO_THROW(bounce->setScene(pointOnly, &ctx()));
}

// The environment's shot adds to the area emitters' in the direct atlas: the Cornell box (open in
// front) under a constant sky, lit by the sky alone, by its emitter alone and by both. Same seed on
// every side, so the emitter points and the environment's directions are the same and the direct
// layers add up to float rounding. The plan names the sources shot, and environment_shots = 0
// leaves the sky to the exchange's list ends. A shot that dropped either source where both exist
// (both = one alone) fails it.
TEST_F(Atlas, EnvironmentShotAddsToTheEmittersShot) {
    Scene areaOnly = loadSmall("data/cornell-box/cornell.toml", 16);
    Scene both = areaOnly;
    both.environment.present = true;
    both.environment.radiance = glm::vec3(0.8f, 0.9f, 1.0f);
    Scene skyOnly = both;
    for (Mesh& m : skyOnly.meshes) m.emission = glm::vec3(0.0f);
    const std::vector<std::string> settings{"atlas_resolution=32", "bundle_resolution=32", "first_shot=on"};
    const auto shot = [&](const Scene& s, const std::vector<std::string>& more = {}) {
        std::vector<std::string> all = settings;
        all.insert(all.end(), more.begin(), more.end());
        return createMode("atlas", all)->plan(s).pass("first-shot");
    };
    EXPECT_EQ(shot(areaOnly).code, "area-emitters");
    EXPECT_EQ(shot(skyOnly).code, "environment");
    EXPECT_EQ(shot(both).code, "area-emitters-environment");
    EXPECT_EQ(shot(skyOnly, {"environment_shots=0"}).code, "environment-shots-0");
    EXPECT_FALSE(shot(skyOnly, {"environment_shots=0"}).runs);
    EXPECT_EQ(shot(both, {"environment_shots=0"}).code, "area-emitters");
    expectDirectLayersAdd(areaOnly, skyOnly, both, settings, "area + sky");
}

// Where the first shot cannot run (transfer = bounce, delay_indirect: their senders are not the
// shot's), first_shot = auto leaves the environment to the exchange's list ends: the Cornell box
// (open in front) under a constant sky and no emitter, lit through the list ends, reflects about
// what the shot gives (the same sky, 16 directions each; bounce keeps the first pass, the sky's
// direct light, as the shot's `direct`). Measured: bounce 0.708 of the shot (its first pass alone),
// delay_indirect 1.014. A condition that dropped the sky from the list ends without shooting it
// would leave the box dark (ratio 0).
TEST_F(Atlas, EnvironmentReachesTheListEndsWhereTheShotCannotRun) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", 16);
    for (Mesh& m : s.meshes) m.emission = glm::vec3(0.0f);
    s.environment.present = true;
    s.environment.radiance = glm::vec3(0.8f, 0.9f, 1.0f);
    const std::vector<std::string> common{"atlas_resolution=32", "bundle_resolution=32"};
    const auto reflected = [&](const std::vector<std::string>& more) {
        std::vector<std::string> settings = common;
        settings.insert(settings.end(), more.begin(), more.end());
        return lumaMean(reflectedLight(run(s, 16, settings)->resolve()));
    };
    const double shot = reflected({});
    for (const std::vector<std::string>& conflict :
         {std::vector<std::string>{"transfer=bounce", "bounce_directions=16"}, std::vector<std::string>{"delay_indirect=4"}}) {
        std::vector<std::string> settings = common;
        settings.insert(settings.end(), conflict.begin(), conflict.end());
        EXPECT_FALSE(createMode("atlas", settings)->plan(s).runs("first-shot")) << conflict[0];
        const double listEnds = reflected(conflict);
        std::printf("reflected light: shot %.5g, %s %.5g (ratio %.3f)\n", shot, conflict[0].c_str(), listEnds,
                    listEnds / shot);
        EXPECT_GT(listEnds, 0.5 * shot) << conflict[0];
        EXPECT_LT(listEnds, 2.0 * shot) << conflict[0];
    }
}

// Delayed indirect light ([HHGM10] section 6.4) on the box lit by its whole ceiling. With
// delay_indirect = N the one-bounce channel (the emitters' light received once: a fixed sender,
// the plain mean over all n directions) is layer `direct`: given the same directions it is the
// first pass of bounce-by-bounce transfer (max_segments = 2), to float rounding (the exchange's
// atomic adds): measured equal to 6 digits. The multi-bounce channel's weighting is checked where
// its expectation is exact (FurnaceDelayedIndirectReachesTwo). Against the reference it is not
// tested here: on this box its seeds spread 2.1% at 160 directions of its own while its bracket
// (deficit + texel bias) is +-1.6%, so the noise gate would need ~64 seeds; the one-bounce channel
// alone would need ~70x the directions (its texel bias, 0.6%, is its whole tolerance, and every
// texel shares each direction's grid offset). Mutation: the one-bounce channel j^k-weighted (fails).
TEST_F(Atlas, CornellDelayedOneBounceChannelIsTheFirstBouncePass) {
    Scene s = loadSmall("data/cornell-box/cornell-ceiling-light.toml", kStatResolution);
    constexpr std::uint32_t kDirections = 96, kDelay = 32;
    const std::vector<std::string> common{"atlas_resolution=128", "bundle_resolution=128", "view_samples=4"};
    std::vector<std::string> delayed = common, firstPass = common;
    delayed.insert(delayed.end(), {"delay_indirect=" + std::to_string(kDelay), "first_shot=off"});
    firstPass.insert(firstPass.end(),
                     {"transfer=bounce", "max_segments=2", "bounce_directions=" + std::to_string(kDirections)});
    double side = 0.0;
    for (std::uint32_t seed : stats::seeds(2)) {
        const ImageSet out = resolveSeed(s, kDirections, delayed, seed, side);
        const double oneBounce = lumaMean(bl::test::layerOf(out, "direct"));
        const double pass = lumaMean(bl::test::layerOf(resolveSeed(s, kDirections, firstPass, seed, side), "rest"));
        std::printf("seed %u: one-bounce channel %.7f, first bounce pass %.7f\n", seed, oneBounce, pass);
        EXPECT_NEAR(oneBounce, pass, 1e-5 * pass) << "seed " << seed;
        EXPECT_GT(lumaMean(bl::test::layerOf(out, "rest")), 0.0) << "seed " << seed << ": no multi-bounce light";
    }
}

// McGuire's CornellBox-Glossy with exact Phong lobes (exponent 40 on the sphere and the short box)
// lit by a point light ([HHGM10] sections 5.3-5.4): the glossy transfer atlas carries light through
// the lobes from surface to surface (the box top throws the light's reflection onto the ceiling,
// the sphere reflects the room), the final gather shows the lobes toward the eye, the highlight
// pass the light's own reflection. As CornellPointLightMatchesReference, on the statistics harness:
// `direct` (the point light once: diffuse by the direct atlas, the highlight per view sample) within
// kShadowTolerance + the texel bias of the direct light; `rest` against the reference's indirect1 +
// indirect2 + rest less the interleaved deficit within the same + the texel bias of the indirect
// light, the transport's norm the largest albedo + specular (the sphere's 0.33 + 0.5). The texel
// average of a lobe over the normals a texel of the sphere spans (+-0.03 rad at 128^2, the lobe's
// width 1 / sqrt(41) = 0.16 rad) is second order, (0.03 / 0.16)^2 / 2 = 2 % of the light the sphere
// reflects glossily, a fraction of `rest`, left out of the bracket. 4 seeds at 512 directions, 128^2
// atlas and bundles:
// direct +2.9 % of its bracket's centre (1.002 of the reference; tolerance 3.8 %), indirect +1.6 %
// (0.993; tolerance 3.3 %), seeds' sd 1.0 %. At 256 directions the glossy transfer's heavy tail
// spreads the seeds by 4 % (too noisy for the gate). Mutation: glossy = gather (no glossy transfer
// atlas): indirect -9.4 % (fails); the old single-seed windows (5 / 4 / 6 %) let it within 3 %.
TEST_F(Atlas, GlossyCornellMatchesReference) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-glossy-point.toml");
    Scene s = loadSmall("data/external/cornell-glossy-point.toml", kStatResolution);
    double norm = 0.0;
    for (const Material& m : s.materials) {
        norm = std::max(norm, double(std::max({m.albedo.x, m.albedo.y, m.albedo.z}) +
                                     std::max({m.specular.x, m.specular.y, m.specular.z})));
    }
    expectDirectAndIndirect(s, 512, {"atlas_resolution=128", "bundle_resolution=128", "view_samples=16"}, 4, norm,
                            kShadowTolerance, "cornell glossy");
}

// An HDR environment map (Bitterli's classroom sky, a sun in it; data/analytic/sky-blocks.toml) over
// blocks, by environment importance (luminance + its mean as offset, each direction weighted by its
// density), the environment's first shot off (environment_shots = 0): each direction's escaping rays
// carry the map's radiance along -omega / +omega, one lookup per direction. The glossy lobe is
// removed for both renderers (the mode is diffuse). As EnvironmentAtListEndsMatchesReference: the
// reflected light of 4 seeds against the reference's, less the interleaved deficit, within the
// texel bias (AtlasBias.h). The bias bound grows with the texel side h, the directions its noise
// needs fall as 1 / tol^2 and each costs h^2 less, so coarse texels with many directions are the
// cheap test: 32^2 at 1024 directions (bracket 0.961 +- 0.044, 8 s) reads 1.001 of the reference,
// seeds' sd 2.1 %. The first shot became the default for environments, so this path (importance
// directions at list ends) went from 64^2 at 4096 directions (tolerance 1.5 %, 69 s: +1.46 % of the
// bracket's centre, seeds' sd 0.30 %) to this cheaper, looser test, which still fails every error
// of the weights' size: the directions' density read as uniform gave +192 %. At 48^2 and 2048
// directions the seeds spread too much for its 2.1 % tolerance (the sun's few directions).
TEST_F(Atlas, EnvironmentMapAtListEndsMatchesReference) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/analytic/sky-blocks.toml");
    Scene s = loadSmall("data/analytic/sky-blocks.toml", kStatResolution);
    for (Material& m : s.materials) m.specular = glm::vec3(0.0f);
    expectReflectedLight(s, 1024,
                         {"atlas_resolution=32", "bundle_resolution=32", "view_samples=16", "directions=importance",
                          "environment_shots=0"},
                         4, kBlocksAlbedo, 1, "sky map");
}

// The same sky by the environment's first shot (the default): each direction, environment_shots = 4
// directions drawn by the map's importance light every texel's sample points through a depth map
// each (layer `direct`), and the exchange carries reflected light only (layer `rest`; its list ends
// receive nothing). As the area light's first shot (CornellFirstShotMatchesReference): `direct`
// against the reference's within the texel bias + the depth maps' contact strips, `rest` against
// the reference's indirect layers less the interleaved deficit within the texel bias + the same
// strip share (AtlasTestFixture.h). 4 seeds x 256 directions at a 64^2 atlas, 512^2 maps: direct
// 0.995 of the reference (+0.66 % of the bracket's centre, tolerance 1.81 %, seeds' sd 0.4 %),
// indirect 0.991 (+5.4 % of the centre, whose indirect texel bias at 64^2 is wide: tolerance 7.1 %),
// in 10 s where the list ends need 4096 directions and 69 s (EnvironmentMapAtListEndsMatchesReference).
// Mutation: the maps' visibility ignored: direct +31 %, indirect +81 % (fail).
TEST_F(Atlas, EnvironmentShotMatchesReference) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/analytic/sky-blocks.toml");
    Scene s = loadSmall("data/analytic/sky-blocks.toml", kStatResolution);
    for (Material& m : s.materials) m.specular = glm::vec3(0.0f);
    constexpr std::uint32_t kMapResolution = 512;
    const double strip = std::sqrt(2.0) * double(s.bounds().radius()) / kMapResolution;
    expectDirectAndIndirect(s, 256,
                            {"atlas_resolution=64", "bundle_resolution=64", "view_samples=16",
                             "environment_shadow_resolution=" + std::to_string(kMapResolution)},
                            4, kBlocksAlbedo, 0.0, "sky map shot", strip);
}


namespace {

double meanOf(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += p.x + p.y + p.z;
    return sum / (3.0 * double(image.pixelCount()));
}

} // namespace

// Light leaks through a wall 1/1000 of the room thick (data/analytic/light-leak.toml): the point
// light's half is lit, the camera's half is dark in the reference (exactly 0). The atlas texels of
// the floor, ceiling and side walls that straddle the wall average both halves, and the exchange
// carries that light into the dark half, where it spreads. Measured as the dark half's image mean
// over the lit half's (camera mirrored; the lit half's mean 3.9 is dominated by the light's close
// walls), 64 directions: 0.0124 at a 64^2 atlas, 0.0023 at 256^2 (0.0005 at 1024^2 by the CLI: it
// falls as 1 / resolution, the straddling texels' width). The bias of the area average, kept and
// stated; the test bounds it and checks that finer texels shrink it.
TEST_F(Atlas, LightLeakShrinksWithTexelSize) {
    Scene dark = loadSmall("data/analytic/light-leak.toml", 32);
    Scene lit = dark;
    lit.camera.pose.position = {0.05f, 0.5f, 0.5f};
    lit.camera.pose.target = {1.0f, 0.5f, 0.5f};
    EXPECT_EQ(meanOf(bl::test::renderReference(dark, 4).radiance()), 0.0);
    double leak[2];
    const int sizes[2] = {64, 256};
    for (int i = 0; i < 2; ++i) {
        const std::vector<std::string> settings{"atlas_resolution=" + std::to_string(sizes[i]), "bundle_resolution=256",
                                                "view_samples=2"};
        const double litMean = meanOf(run(lit, 64, settings)->resolve().radiance());
        const double darkMean = meanOf(run(dark, 64, settings)->resolve().radiance());
        leak[i] = darkMean / litMean;
        std::printf("light leak: atlas %d^2, lit half %.5f, dark half %.5f, leak %.4f\n", sizes[i], litMean, darkMean,
                    leak[i]);
    }
    EXPECT_LT(leak[0], 0.025);
    EXPECT_LT(leak[1], 0.005);
    EXPECT_LT(leak[1], leak[0] / 3.0);
}

// The pass plan: the Cornell box has no point light, no environment and no glossy material, so the
// shadow maps and the glossy passes are skipped and no list end receives anything. Forcing them to
// run (a point light of zero intensity, a black constant sky, a glossy material on no mesh) leaves
// every pixel as it was: skipping them changes nothing.
TEST_F(Atlas, SkippedPassesLeaveTheImageUnchanged) {
    Scene plain = loadSmall("data/cornell-box/cornell.toml", 32);
    Scene forced = plain;
    Light off;
    off.position = {278.0f, 500.0f, 279.5f};
    off.intensity = glm::vec3(0.0f);
    forced.lights.push_back(off);
    forced.environment.present = true;
    forced.environment.radiance = glm::vec3(0.0f);
    Material unused; // glossy, on no mesh: the glossy transfer, gather and highlight passes run
    unused.name = "unused-glossy";
    unused.specular = glm::vec3(0.5f);
    unused.exponentU = unused.exponentV = 40.0f;
    forced.materials.push_back(unused);
    // The exchange carries the emitters' light on both sides: with first_shot = auto the unused
    // glossy material would leave the shot out of `forced` alone.
    const std::vector<std::string> settings{"atlas_resolution=128", "bundle_resolution=128", "view_samples=2",
                                            "first_shot=off"};
    auto passRuns = [&](const Scene& s, const std::string& id) { return createMode("atlas", settings)->plan(s).runs(id); };
    EXPECT_FALSE(passRuns(plain, "light-shadow-cubes"));
    EXPECT_TRUE(passRuns(forced, "light-shadow-cubes"));
    EXPECT_FALSE(passRuns(plain, "glossy-transfer"));
    EXPECT_FALSE(passRuns(plain, "glossy-gather"));
    EXPECT_TRUE(passRuns(forced, "glossy-transfer"));
    EXPECT_TRUE(passRuns(forced, "glossy-gather"));
    const Image a = run(plain, 32, settings)->resolve().radiance();
    const Image b = run(forced, 32, settings)->resolve().radiance();
    double worst = 0.0;
    for (std::size_t p = 0; p < a.pixelCount(); ++p) {
        worst = std::max(worst, double(glm::length(a.pixels()[p] - b.pixels()[p])));
    }
    std::printf("plan: largest pixel difference with the skipped passes forced %.3g (image mean %.4f)\n", worst,
                meanOf(a));
    EXPECT_GT(meanOf(a), 0.01);
    EXPECT_LE(worst, 1e-6 * meanOf(a));
}
