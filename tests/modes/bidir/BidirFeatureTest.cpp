// Mode bidir beyond its estimators' convergence: plans that skip work leave the image unchanged,
// VPL shadow taps, scenes without point lights, fitted frames, environment bundles, textured albedo,
// reflective shadow maps against traced VPLs, spot lights (the fixture: BidirTestFixture.h).
#include "modes/bidir/BidirTestFixture.h"
#include "support/AnalyticScenes.h"

using namespace bl::test::bidirmode;

// The pass plan skips glossy suppression on a scene without glossy materials, and the image is
// the same to the bit as with suppression = none; on the glossy scene it runs and changes the
// image (so the comparison can fail).
TEST_F(Bidir, PlanSkipsSuppressionWithoutGlossyMaterialImageUnchanged) {
    auto render = [&](const Scene& s, const std::string& suppression, bool expectRuns) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "suppression=" + suppression});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        const PlannedPass p = mode->plan(s).pass("glossy-suppression");
        EXPECT_EQ(p.runs, expectRuns) << suppression << ": " << p.reason;
        EXPECT_EQ(p.code, expectRuns ? "glossy-vertices" : suppression == "none" ? "suppression-none" : "no-glossy-material");
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 4; ++f) mode->iterate({f, 7, 0.0});
        ImageSet out = mode->resolve();
        return std::make_pair(bl::test::layerOf(out, "indirect1"), bl::test::layerOf(out, "indirect2"));
    };
    auto same = [](const Image& a, const Image& b) {
        for (int y = 0; y < kResolution; ++y)
            for (int x = 0; x < kResolution; ++x)
                if (a.at(x, y) != b.at(x, y)) return false;
        return true;
    };
    const Scene diffuse = cornellPoint();
    const auto skipped = render(diffuse, "roughness", false);
    const auto none = render(diffuse, "none", false);
    EXPECT_TRUE(same(skipped.first, none.first) && same(skipped.second, none.second));

    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-glossy-point.toml");
    Scene glossy = loadScene(bl::test::sourcePath("data/external/cornell-glossy-point.toml"));
    glossy.camera.resolution = {kResolution, kResolution};
    const auto suppressed = render(glossy, "roughness", true);
    const auto glossyNone = render(glossy, "none", false);
    EXPECT_FALSE(same(suppressed.first, glossyNone.first));
}

// vpl_shadow_taps (specialization constant) changes only the filter of the two VPL-cube lookups:
// `direct` (the lights' cubes, 4x4 PCF) is the same to the bit, indirect light changes (the taps
// are applied) by no more than a filter's worth, and no sample is non-finite at 1, 2 or 3 taps.
TEST_F(Bidir, VplShadowTapsChangeOnlyTheVplShadowFilter) {
    const Scene s = cornellPoint();
    auto render = [&](int taps) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", "vpl_shadow_taps=" + std::to_string(taps)});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 8; ++f) mode->iterate({f, 3, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u) << taps << " taps";
        return out;
    };
    const ImageSet four = render(4);
    const double four1 = channelMeans(bl::test::layerOf(four, "indirect1")).y;
    const double four2 = channelMeans(bl::test::layerOf(four, "indirect2")).y;
    ASSERT_GT(four1, 0.0);
    for (int taps : {1, 2, 3}) {
        const ImageSet out = render(taps);
        const Image& direct = bl::test::layerOf(out, "direct");
        const Image& directFour = bl::test::layerOf(four, "direct");
        bool sameDirect = true, changed = false;
        const Image& ind = bl::test::layerOf(out, "indirect1");
        const Image& indFour = bl::test::layerOf(four, "indirect1");
        for (int y = 0; y < kResolution; ++y) {
            for (int x = 0; x < kResolution; ++x) {
                sameDirect = sameDirect && direct.at(x, y) == directFour.at(x, y);
                changed = changed || ind.at(x, y) != indFour.at(x, y);
            }
        }
        const double r1 = channelMeans(ind).y / four1;
        const double r2 = channelMeans(bl::test::layerOf(out, "indirect2")).y / four2;
        std::printf("vpl_shadow_taps %d / 4: indirect1 %.4f, indirect2 %.4f\n", taps, r1, r2);
        EXPECT_TRUE(sameDirect) << taps << " taps";
        EXPECT_TRUE(changed) << taps << " taps: the VPL lookups ignore the setting";
        EXPECT_NEAR(r1, 1.0, 0.02) << taps << " taps";
        EXPECT_NEAR(r2, 1.0, 0.04) << taps << " taps";
    }
}

// A scene without point or spot lights whose area emitters are left out (emitter_points = 0): no
// VPLs, no bundles, no pool bound; every strategy renders the emitters and nothing else (it read
// the unbound pool's address 0 and crashed the device before), as the plan says.
TEST_F(Bidir, SceneWithoutPointLightsRendersEmittersOnly) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    s.camera.resolution = {16, 16};
    for (const char* strategy : {"vpl", "bundle", "mis"}) {
        std::unique_ptr<Mode> mode =
            createMode("bidir", {std::string("strategy=") + strategy, "pairs_per_frame=2", "emitter_points=0"});
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 2; ++f) mode->iterate({f, 1, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        double emitted = 0.0, rest = 0.0;
        for (int y = 0; y < 16; ++y) {
            for (int x = 0; x < 16; ++x) {
                emitted += luminance(bl::test::layerOf(out, "emitted").at(x, y));
                for (const char* layer : {"direct", "indirect1", "indirect2"}) {
                    rest += luminance(bl::test::layerOf(out, layer).at(x, y));
                }
            }
        }
        EXPECT_GT(emitted, 0.0) << strategy;
        EXPECT_EQ(rest, 0.0) << strategy;
    }
}

// The area-lit Cornell box (data/cornell-box/cornell.toml: no point light): direct light by emitter
// points, one-bounce light by MIS of the bundle strategy with emitter points at its hits and the
// area VPLs (VplSampler.h), against
// the reference's direct and indirect1 layers over 8 seeds: direct region by region within
// kTolerance (the points' one-tap cubes move contact shadows by under 0.5%: MultibounceTest's
// kEmitterShadowTolerance), indirect1 region by region within kNoisyTolerance (bundle pixels move
// the bundle side's visibility boundaries; dim regions floored at kDimRegion), both image means
// within kImageTolerance; indirect2 stays empty (bounces = 1). Mutations: the bundle term's emitter
// light left out (indirect1 keeps only the VPLs' MIS share), the direct layer's (direct 0).
TEST_F(Bidir, AreaLightByEmitterPointsConvergesToReferenceLayers) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    s.camera.resolution = {kResolution, kResolution};
    constexpr std::uint32_t kAreaFrames = 64, kAreaSeeds = 8;
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    std::vector<std::vector<double>> direct, indirect;
    double indirect2 = 0.0;
    for (std::uint32_t seed : stats::seeds(kAreaSeeds)) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=1"});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kAreaFrames; ++f) mode->iterate({f, seed, 0.0});
        const ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        direct.push_back(regionMeans(bl::test::layerOf(out, "direct")));
        indirect.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        indirect2 += imageMean(regionMeans(bl::test::layerOf(out, "indirect2")));
    }
    expectConverged(direct, regionMeans(bl::test::layerOf(reference, "direct")), kTolerance, "area light direct",
                    kDimRegion);
    expectConverged(indirect, regionMeans(bl::test::layerOf(reference, "indirect1")), kNoisyTolerance,
                    "area light indirect1", kDimRegion);
    EXPECT_EQ(indirect2, 0.0);
}

// The area VPLs on their own (strategy = vpl, bounces = 2; the same box): x0 on the emitter by
// power, a cosine-weighted ray, the VPL where it lands, as if a point light of intensity
// L_e cos0 / p_A had sent it with density cos0 / pi (VplSampler.h). Their one-bounce term alone
// against the reference's indirect1, and the two-bounce term (the only strategy for indirect2)
// against its indirect2: image means within kNoisyTolerance (the single strategies' and the
// two-bounce term's, BidirTestFixture.h) over 8 seeds x 32 frames of 16 pairs. Measured at 8 x 128:
// indirect1 -0.95 +- 0.79 %, indirect2 -0.92 +- 0.82 % (stderr); kImageTolerance's gate would need
// about 8 x 256 (each frame renders 16 VPL cubes and 16 bundles). Before the area source both layers
// were 0 here. Mutation: the area VPL's intensity without its cos0 (L_e / p_A) fails both.
TEST_F(Bidir, AreaVplsAloneConvergeToReferenceLayers) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    s.camera.resolution = {kResolution, kResolution};
    constexpr std::uint32_t kAreaFrames = 32, kAreaSeeds = 8;
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    std::vector<std::vector<double>> indirect1, indirect2;
    for (std::uint32_t seed : stats::seeds(kAreaSeeds)) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=vpl", "bounces=2", "pairs_per_frame=16"});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kAreaFrames; ++f) mode->iterate({f, seed, 0.0});
        const ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        indirect1.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        indirect2.push_back(regionMeans(bl::test::layerOf(out, "indirect2")));
    }
    expectImageMeanConverged(indirect1, regionMeans(bl::test::layerOf(reference, "indirect1")), "area VPLs indirect1",
                             kNoisyTolerance);
    expectImageMeanConverged(indirect2, regionMeans(bl::test::layerOf(reference, "indirect2")), "area VPLs indirect2",
                             kNoisyTolerance);
}

// Both sources at once (the box lit by its emitter and a point light), vpl_source = rsm (the
// default): the source probability 1/2 must agree between the VPL records (the RSM's pairs and the
// host's area pairs), the lights' density in the MIS weights (lightAt) and the emitter points'
// vplDensity. MIS (bounces = 2, 48 frames, kMisVplCubes), 8 seeds, against the reference's image
// means: indirect1 within kImageTolerance, indirect2 within kNoisyTolerance. Mutation: lightAt's
// density over the L lights instead of the L + 1 sources: indirect1 -6.0 % (fails; unmutated
// -2.0 +- 0.7 %, indirect2 +1.5 +- 1.9 %; the VPLs alone at 32 frames -0.6 +- 1.8 %, not run here
// for the suite's time: AreaVplsAloneConvergeToReferenceLayers runs them without point lights).
TEST_F(Bidir, AreaAndPointVplsShareTheSourcesUnbiased) {
    Scene box = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    box.camera.resolution = {kResolution, kResolution};
    const Scene both = bl::test::areaAndPointLit(box, {278.0f, 400.0f, 279.5f}).both;
    const ImageSet reference = bl::test::renderReference(both, kReferenceSpp);
    const std::vector<double> reference1 = regionMeans(bl::test::layerOf(reference, "indirect1"));
    const std::vector<double> reference2 = regionMeans(bl::test::layerOf(reference, "indirect2"));
    std::vector<std::vector<double>> indirect1, indirect2;
    for (std::uint32_t seed : stats::seeds(8)) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=mis", "bounces=2", kMisVplCubes});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(both, &ctx());
        for (std::uint32_t f = 0; f < 48; ++f) mode->iterate({f, seed, 0.0});
        const ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        indirect1.push_back(regionMeans(bl::test::layerOf(out, "indirect1")));
        indirect2.push_back(regionMeans(bl::test::layerOf(out, "indirect2")));
    }
    expectImageMeanConverged(indirect1, reference1, "both lit indirect1", kImageTolerance);
    expectImageMeanConverged(indirect2, reference2, "both lit indirect2", kNoisyTolerance);
}

// vpl_source = rsm with area emitters: the cubes' sampling pass draws the source among the L lights
// and the area one (P = 1 / (L + 1)); the pairs that draw the area source are left unwritten there
// and listed for the host to trace (VplSampler::areaVpl). On the box lit by its emitter and one
// point light, 4096 pairs: the listed share is 1/2 within 4 binomial sigmas (+-3.1 %), no listed
// pair carries a VPL, every other one is the VPL the same pair gives without the area source (the
// texel draw is the pair's own) with half its density: P = 1/2 against 1.
TEST_F(Bidir, RsmLeavesTheAreaSourcesPairsToTheHost) {
    Scene box = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    const Scene both = bl::test::areaAndPointLit(box, {278.0f, 400.0f, 279.5f}).both;
    gpu::GpuScene gpuScene(ctx(), both);
    ReflectiveShadowMap rsm(ctx(), gpuScene, 64);
    constexpr std::uint32_t kCount = 4096;
    std::vector<std::uint32_t> areaPairs;
    const std::vector<shader::BidirVpl> vpls = rsm.sample(0, kCount, 3, 0.0, 0.01f, nullptr, true, areaPairs);
    std::vector<std::uint32_t> none;
    const std::vector<shader::BidirVpl> lightOnly = rsm.sample(0, kCount, 3, 0.0, 0.01f, nullptr, false, none);
    EXPECT_TRUE(none.empty());
    const double share = double(areaPairs.size()) / kCount;
    std::printf("area source's share of %u pairs: %.4f\n", kCount, share);
    EXPECT_NEAR(share, 0.5, 4.0 * std::sqrt(0.25 / kCount));
    std::vector<bool> listed(kCount, false);
    for (std::uint32_t k : areaPairs) listed[k] = true;
    std::uint32_t valid = 0;
    for (std::uint32_t k = 0; k < kCount; ++k) {
        if (listed[k]) {
            EXPECT_EQ(vpls[k].valid, 0u) << "pair " << k;
            continue;
        }
        EXPECT_EQ(vpls[k].valid, lightOnly[k].valid) << "pair " << k;
        if (!vpls[k].valid) continue;
        ++valid;
        EXPECT_EQ(vpls[k].light, 0u);
        EXPECT_EQ(vpls[k].position, lightOnly[k].position) << "pair " << k;
        EXPECT_FLOAT_EQ(vpls[k].pdfLight, 0.5f * lightOnly[k].pdfLight) << "pair " << k;
    }
    EXPECT_GT(valid, kCount / 4);
}

// A box lit by both its area emitter and a point light: the emitter points' light adds to the point
// light's in every layer (strategy = bundle: the same bundles and emitter points on every side; the
// VPLs would not be the same, their sources being drawn among both), so direct and indirect1 of
// both lit = area alone + point alone to float rounding. Mutation: the bundle term's emitter light
// only where there are no point lights breaks the sum (fails).
TEST_F(Bidir, AreaAndPointLightsAdd) {
    Scene box = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    box.camera.resolution = {16, 16};
    const bl::test::AreaAndPointLit lit = bl::test::areaAndPointLit(box, {278.0f, 400.0f, 279.5f});
    const Scene &area = lit.area, &pointOnly = lit.pointOnly, &both = lit.both;
    const auto means = [&](const Scene& s) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=bundle", "bounces=1"});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 2; ++f) mode->iterate({f, 5, 0.0});
        const ImageSet out = mode->resolve();
        return glm::dvec2(imageMean(regionMeans(bl::test::layerOf(out, "direct"))),
                          imageMean(regionMeans(bl::test::layerOf(out, "indirect1"))));
    };
    const glm::dvec2 a = means(area), p = means(pointOnly), ab = means(both);
    std::printf("direct: area %.6g + point %.6g = %.6g, both %.6g; indirect1: %.6g + %.6g = %.6g, both %.6g\n", a.x,
                p.x, a.x + p.x, ab.x, a.y, p.y, a.y + p.y, ab.y);
    for (int i = 0; i < 2; ++i) {
        EXPECT_GT(a[i], 0.05 * p[i]) << i;
        EXPECT_GT(p[i], 0.05 * a[i]) << i;
        EXPECT_NEAR(ab[i], a[i] + p[i], 1e-4 * (a[i] + p[i])) << (i ? "indirect1" : "direct");
    }
}

// Bundle frames fitted to the points the G-buffer sees ([TO12s] B.1) drop no sample (every camera
// point falls inside every bundle, jittered G-buffer included) and use smaller pixels than the
// scene's sphere for the same bundle_resolution; the convergence tests run with this fit (the
// default), VisibleFitFindsHitsBeyondTheVisiblePoints with hits no camera point sees.
TEST_F(Bidir, VisibleFitCoversEveryCameraPointWithSmallerPixels) {
    double effective[2] = {0.0, 0.0};
    const Scene s = cornellPoint();
    for (const char* fit : {"scene", "visible"}) {
        std::vector<std::string> settings = kCommon;
        settings.insert(settings.end(), {"strategy=bundle", "bounces=1", std::string("fit=") + fit});
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < 8; ++f) mode->iterate({f, 3, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0) << fit;
        effective[fit[0] == 'v'] = counterOf(out, "bundle_effective_resolution");
    }
    std::printf("effective bundle resolution: scene %.1f, visible %.1f\n", effective[0], effective[1]);
    EXPECT_DOUBLE_EQ(effective[0], 128.0);
    EXPECT_GT(effective[1], 128.0);
}

// Direct environment light by environment bundles ([TO12] section 3, Eq. 2 importance directions):
// on the sky-blocks scene (no point light: no pairs) the `direct` layer converges to the
// reference's region by region and in its image mean, no sample dropped; with
// environment_bundles = 0 the plan skips the pass and `direct` is zero.
TEST_F(Bidir, EnvironmentBundlesConvergeToReferenceDirect) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/analytic/sky-blocks.toml");
    Scene s = loadScene(bl::test::sourcePath("data/analytic/sky-blocks.toml"));
    s.camera.resolution = {kResolution, kResolution};
    const std::vector<double> reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "direct"));
    std::vector<std::vector<double>> perSeed;
    for (std::uint32_t seed : stats::seeds(kSeeds)) {
        std::vector<std::string> settings = kCommon;
        settings.push_back("environment_bundles=" + std::to_string(kEnvironmentBundles));
        std::unique_ptr<Mode> mode = createMode("bidir", settings);
        EXPECT_EQ(mode->plan(s).pass("environment-bundles").code, "importance-directions");
        mode->setScene(s, &ctx());
        for (std::uint32_t f = 0; f < kEnvironmentFrames; ++f) mode->iterate({f, seed, 0.0});
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        EXPECT_EQ(counterOf(out, "dropped_samples"), 0.0);
        perSeed.push_back(regionMeans(bl::test::layerOf(out, "direct")));
    }
    // Regions that see mostly sky (direct light below 5% of the mean region's) left out of the
    // region test; the image mean keeps them.
    double meanRegion = 0.0;
    for (double r : reference) meanRegion += r / double(reference.size());
    std::vector<double> litReference;
    std::vector<std::vector<double>> litPerSeed(perSeed.size());
    for (std::size_t i = 0; i < reference.size(); ++i) {
        if (reference[i] < 0.05 * meanRegion) continue;
        litReference.push_back(reference[i]);
        for (std::size_t k = 0; k < perSeed.size(); ++k) litPerSeed[k].push_back(perSeed[k][i]);
    }
    EXPECT_TRUE(stats::regionsAgree(litPerSeed, litReference, {kEnvironmentTolerance, 0.0, stats::kAlpha},
                                    "environment direct (lit regions)"));
    expectImageMeanConverged(perSeed, reference, "environment direct", kEnvironmentTolerance);

    std::unique_ptr<Mode> off = createMode("bidir", {"environment_bundles=0", "pairs_per_frame=2"});
    EXPECT_FALSE(off->plan(s).runs("environment-bundles"));
    EXPECT_EQ(off->plan(s).pass("environment-bundles").code, "environment-bundles-0");
    off->setScene(s, &ctx());
    off->iterate({0, 1, 0.0});
    double direct = 0.0;
    const Image image = bl::test::layerOf(off->resolve(), "direct");
    for (int y = 0; y < kResolution; ++y)
        for (int x = 0; x < kResolution; ++x) direct += luminance(image.at(x, y));
    EXPECT_EQ(direct, 0.0);
}

// Textured albedo at bundle hits (the payload's UV in the packed texture buffer) and at RSM VPLs
// (the RSM's G-buffer): the point-lit box with a red/green floor, whose untextured white would put
// indirect1's blue channel far off (+17% for multibounce's same scene). What the texture changes is
// the balance of the channels: per seed each channel's share of indirect1's channel sum against the
// reference's (the VPLs' and bundles' noise, which all channels of a run share, cancels in the
// shares: 8 seeds x 32 frames put the channels' own means at 1.4% (bundle) to 4.8% (RSM VPLs)
// standard error, too noisy for kImageTolerance; their overall level is the untextured tests' job).
// The shares spread less: 0.4-1.0% (bundle) and 1.0-1.3% (RSM VPLs) standard error at 8 x 32, so
// they are held to kTolerance (the gate needs 3 x 1.3%), a third of what the missing texture does.
TEST_F(Bidir, TexturedAlbedoAtBundleHitsAndRsmVpls) {
    Scene s = cornellPoint();
    ASSERT_TRUE(bl::test::texturePlanar(s, "floor", bl::test::redGreenTexture()));
    const ImageSet ref = bl::test::renderReference(s, kReferenceSpp);
    const glm::dvec3 reference = channelMeans(bl::test::layerOf(ref, "indirect1"));
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"strategy=bundle", "bounces=1"},
          std::vector<std::string>{"strategy=vpl", "bounces=1", "vpl_source=rsm"}}) {
        std::vector<double> channels[3];
        for (std::uint32_t seed : stats::seeds(kSeeds)) {
            std::vector<std::string> settings = kCommon;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (std::uint32_t f = 0; f < kTexturedFrames; ++f) mode->iterate({f, seed, 0.0});
            const glm::dvec3 m = channelMeans(bl::test::layerOf(mode->resolve(), "indirect1"));
            for (int c = 0; c < 3; ++c) channels[c].push_back(m[c]);
        }
        const double referenceSum = reference.x + reference.y + reference.z;
        for (int c = 0; c < 3; ++c) {
            std::vector<double> shares;
            for (std::size_t k = 0; k < channels[c].size(); ++k) {
                shares.push_back(channels[c][k] / (channels[0][k] + channels[1][k] + channels[2][k]));
            }
            const stats::Summary sc = stats::summarize(shares);
            const double share = reference[c] / referenceSum;
            std::printf("%s: indirect1 channel %d share %.5f +- %.5f reference %.5f (%+.2f%%)\n", extra[0].c_str(), c,
                        sc.mean, sc.stderr_, share, 100.0 * (sc.mean / share - 1.0));
            EXPECT_TRUE(stats::agrees(sc, share, kTolerance * share, extra[0] + " indirect1 channel share " +
                                                                         std::to_string(c)));
        }
    }
}

// The RSM's VPLs (vpl_source = rsm) against traced ones (CPU rays, Embree: an independent sampler
// with an exact first hit): both estimate the same integral at fixed floor points x, the one-bounce
// light from every directly lit surface without the visibility y - x,
//   E[ I(omega) f_y f_x cos_y cos_x / (|y - x|^2 p_e(omega) P(l)) ],
// so any error in the RSM's VPL positions, normals, p_e or intensity shows, and nothing of the
// rendering does. 262,144 VPLs of each source; a point light (p_e near uniform) and a spot light
// with a 20-degree smooth edge (the RSM's p_e follows I(omega), the traced one is uniform in the
// cone: different densities, the same expectation).
TEST_F(Bidir, RsmVplsEstimateWhatTracedVplsEstimate) {
    constexpr std::uint32_t kCount = 4096, kRounds = 64;
    for (const bool spot : {false, true}) {
        Scene s = cornellPoint();
        if (spot) {
            s.lights[0].type = Light::Type::Spot;
            s.lights[0].direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.3f));
            s.lights[0].coneAngleDegrees = 50.0f;
            s.lights[0].falloffDegrees = 20.0f;
        }
        gpu::GpuScene gpuScene(ctx(), s);
        ReflectiveShadowMap rsm(ctx(), gpuScene, 64);
        VplSampler traced(s, false);
        for (const glm::vec3 x : {glm::vec3(278.0f, 0.5f, 60.0f), glm::vec3(100.0f, 0.5f, 100.0f),
                                  glm::vec3(450.0f, 0.5f, 30.0f)}) {
            double sum[2] = {0.0, 0.0}, sum2[2] = {0.0, 0.0};
            for (std::uint32_t r = 0; r < kRounds; ++r) {
                std::vector<std::uint32_t> noAreaPairs;
                const std::vector<shader::BidirVpl> vpls[2] = {rsm.sample(std::uint64_t(r) * kCount, kCount, 9, 0.0, 0.01f,
                                                                          nullptr, false, noAreaPairs),
                                                               traced.sample(std::uint64_t(r) * kCount, kCount, 9, 0.0, 0.01f)};
                for (int source = 0; source < 2; ++source) {
                    for (const shader::BidirVpl& v : vpls[source]) {
                        const glm::vec3 d = x - v.position;
                        const float r2 = glm::dot(d, d);
                        const glm::vec3 w = d / std::sqrt(r2);
                        const float cosY = glm::dot(v.normal, w), cosX = -w.y; // the floor faces +y
                        if (!v.valid || cosY <= 0.0f || cosX <= 0.0f) continue;
                        const double c = luminance(v.intensity * v.albedo) * cosY * cosX / (r2 * v.pdfLight);
                        sum[source] += c;
                        sum2[source] += c * c;
                    }
                }
            }
            const double n = double(kCount) * kRounds;
            double mean[2], sigma[2];
            for (int source = 0; source < 2; ++source) {
                mean[source] = sum[source] / n;
                sigma[source] = std::sqrt(std::max(0.0, sum2[source] / n - mean[source] * mean[source]) / n);
            }
            const double combined = std::hypot(sigma[0], sigma[1]);
            std::printf("%s light, x (%.0f %.0f %.0f): rsm %.5g +- %.2g, traced %.5g +- %.2g (%+.2f%%, %+.1f sigma)\n",
                        spot ? "spot" : "point", x.x, x.y, x.z, mean[0], sigma[0], mean[1], sigma[1],
                        100.0 * (mean[0] / mean[1] - 1.0), (mean[0] - mean[1]) / combined);
            EXPECT_LT(combined, 0.02 * mean[1]) << "too noisy to test";
            EXPECT_NEAR(mean[0], mean[1], 4.0 * combined) << (spot ? "spot" : "point");
        }
    }
}

// Traced VPLs of a spot light leave it with p_e = I(omega) / integral(I) ([TO12] 4.1; VplSampler's
// inversion of the profile's CDF, blBidirEmissionPdf), checked against the profile itself
// (blLightProfile integrated by the midpoint rule over cos(theta), not the sampler's closed form):
// the share of rays in each band of cos(theta) about the axis is the band's share of the
// integral (the inner cone, and the smoothstep ring in four parts; binomial errors), and I / p_e
// is the whole integral for every ray. A spot pointing down with a 25-degree cone meets the floor
// everywhere (no ray escapes). 65,536 rays, well under a second.
TEST_F(Bidir, TracedSpotVplsFollowTheProfile) {
    Scene s = cornellPoint();
    s.lights[0].type = Light::Type::Spot;
    s.lights[0].direction = glm::vec3(0.0f, -1.0f, 0.0f);
    s.lights[0].coneAngleDegrees = 25.0f;
    s.lights[0].falloffDegrees = 15.0f;
    const shader::GpuLight light = toGpuLight(s.lights[0]);
    // Integral of the profile over cos in (lo, hi] (times 2 pi: over the solid angle of the band).
    auto integral = [&](double lo, double hi) {
        constexpr int kSteps = 200000;
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i) {
            const double c = lo + (hi - lo) * (i + 0.5) / kSteps;
            const double sine = std::sqrt(std::max(0.0, 1.0 - c * c));
            sum += shader::blLightProfile(light, glm::vec3(float(sine), float(-c), 0.0f));
        }
        return 2.0 * 3.14159265358979 * sum * (hi - lo) / kSteps;
    };
    VplSampler traced(s, false);
    constexpr std::uint32_t kCount = 65536;
    const std::vector<shader::BidirVpl> vpls = traced.sample(0, kCount, 5, 0.0, 0.01f);
    const double cosInner = light.cosInner, cosOuter = light.cosOuter;
    std::vector<double> edges = {1.0, cosInner};
    for (int i = 1; i <= 4; ++i) edges.push_back(cosInner + (cosOuter - cosInner) * i / 4.0);
    std::vector<double> count(edges.size() - 1, 0.0);
    const double total = integral(cosOuter, 1.0);
    double worst = 0.0;
    for (const shader::BidirVpl& v : vpls) {
        ASSERT_EQ(v.valid, 1u);
        const glm::vec3 omega = -v.toLight;
        const double c = glm::dot(omega, light.direction);
        const double ratio = shader::blLightProfile(light, omega) / v.pdfLight / total;
        worst = std::max(worst, std::abs(ratio - 1.0));
        for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
            if (c <= edges[b] && c > edges[b + 1]) count[b] += 1.0;
        }
    }
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        const double p = integral(edges[b + 1], edges[b]) / total;
        const double share = count[b] / kCount;
        const double sigma = std::sqrt(p * (1.0 - p) / kCount);
        std::printf("spot band cos (%.4f, %.4f]: share %.5f, expected %.5f +- %.5f (%+.1f sigma)\n", edges[b + 1],
                    edges[b], share, p, sigma, (share - p) / sigma);
        EXPECT_NEAR(share, p, 4.0 * sigma) << "band " << b;
    }
    // p_e proportional to I: I / p_e is the profile's integral for every ray (float precision).
    std::printf("spot: largest |I / (p_e integral) - 1| %.2g\n", worst);
    EXPECT_LT(worst, 1e-4) << "p_e not I / integral(I)";
}

namespace {
// The point-lit box with its light turned into a spot toward the red wall's foot (40-degree cone,
// 15-degree smooth edge): most of the box is lit only indirectly.
Scene cornellSpot() {
    Scene s = cornellPoint();
    s.lights[0].type = Light::Type::Spot;
    s.lights[0].direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.15f));
    s.lights[0].coneAngleDegrees = 40.0f;
    s.lights[0].falloffDegrees = 15.0f;
    return s;
}
} // namespace

// VPLs from reflective shadow cubes (vpl_source = rsm, the default) against the reference, region
// by region, on the point-lit box and on the spot-lit one (the RSM's p_e follows the profile):
// MIS with bounces = 1, whose balance heuristic bounds the VPL term's 1/r^2 near corners (the VPL
// strategy alone has a tail that a few seeds cannot bound, see RsmVplStrategyImageMean...), so a
// wrong VPL position, normal, albedo, intensity or density shows in its region. 8 seeds x 64
// frames per light, regions within kRsmMisTolerance.
TEST_F(Bidir, RsmVplsConvergeRegionByRegion) {
    for (const bool spot : {false, true}) {
        const Scene s = spot ? cornellSpot() : cornellPoint();
        const std::vector<double> reference = regionMeans(bl::test::layerOf(bl::test::renderReference(s, kReferenceSpp), "indirect1"));
        const Runs r = renderSeeds(s, {"strategy=mis", "bounces=1", "vpl_source=rsm", kMisVplCubes}, kFastFrames);
        expectConverged(r.final1, reference, kRsmMisTolerance, spot ? "rsm mis, spot" : "rsm mis, point",
                        kDimRegion);
    }
}

// Bundle frames fitted to the visible points (fit = visible, the default) must still find every
// surface along a visible point's ray, not only visible ones: the camera looks straight down at the
// floor and the blocks' tops, so a bundle's next vertex y is almost always a wall, the ceiling or
// a block's side, none of them seen. MIS with the two-bounce term (whose second vertex is that
// hit): indirect1 converges to the reference region by region, indirect2 in the image mean (its
// regions carry the unclamped term's 1/r^2 tail). 8 seeds x 64 frames; the walls' regions seen at
// grazing angles spread their seeds by 3.5% at 32 frames (2.5% at 64), so the regions are held to
// kNoisyTolerance, and so is the image mean (1.7% standard error at 64 frames), ample for the
// mutation this test is for: the bundles' depth range fitted to the visible points too (indirect1
// -24.8%, indirect2 -78.6%).
TEST_F(Bidir, VisibleFitFindsHitsBeyondTheVisiblePoints) {
    Scene s = cornellPoint();
    s.camera.pose.position = glm::vec3(278.0f, 540.0f, 279.5f);
    s.camera.pose.target = glm::vec3(278.0f, 0.0f, 279.5f);
    s.camera.pose.up = glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.fovDegrees = 50.0f;
    const ImageSet ref = bl::test::renderReference(s, kReferenceSpp);
    const std::vector<double> reference1 = regionMeans(bl::test::layerOf(ref, "indirect1"));
    const std::vector<double> reference2 = regionMeans(bl::test::layerOf(ref, "indirect2"));
    const Runs r = renderSeeds(s, {"strategy=mis", "bounces=2", "fit=visible"}, kFastFrames);
    expectConverged(r.final1, reference1, kNoisyTolerance, "visible fit, floor view, mis", 0.0, kNoisyTolerance);
    expectImageMeanConverged(r.final2, reference2, "visible fit, floor view, two-bounce",
                             kFloorViewTwoBounceTolerance);
}
