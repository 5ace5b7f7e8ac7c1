// Mode atlas against closed forms and the CPU reference path tracer (never against itself).
#include "base/Error.h"
#include "image/Metrics.h"
#include "modes/Registry.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <cstdio>

using namespace bl;

namespace {

class Atlas : public bl::test::VulkanTest {
protected:
    std::unique_ptr<Mode> run(const Scene& scene, std::uint32_t directions, const std::vector<std::string>& settings,
                              std::uint64_t seed = 1) {
        std::unique_ptr<Mode> mode = createMode("atlas", settings);
        mode->setScene(scene, &ctx());
        for (std::uint32_t i = 0; i < directions; ++i) {
            mode->iterate({i, seed, 0.0});
        }
        return mode;
    }
};

Scene loadSmall(const std::string& path, int resolution) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {resolution, resolution};
    return s;
}

// Radiance of the furnace's inner (front) sides against `expected`: the area-weighted mean, the
// largest deviation of a texel, and the texels counted.
struct FurnaceStats {
    double mean = 0.0, worst = 0.0;
    std::size_t counted = 0;
};
FurnaceStats furnaceStats(const Mode& mode, double expected) {
    const AtlasMode::TexelRadiance texels = static_cast<const AtlasMode&>(mode).readTexels();
    FurnaceStats f;
    double areaSum = 0.0;
    for (std::size_t t = 0; t < texels.area.size(); ++t) {
        if (texels.area[t] <= 0.0f) continue;
        const double l = texels.emission[t].x + texels.reflected[2 * t].x; // the inner side is the front
        f.worst = std::max(f.worst, std::abs(l - expected));
        f.mean += l * texels.area[t];
        areaSum += texels.area[t];
        ++f.counted;
    }
    f.mean /= areaSum;
    return f;
}

} // namespace

// A closed box of albedo 1/2 emitting radiance 1 inward everywhere: the radiance of every texel's
// inner side is 1 / (1 - 1/2) = 2. Checks the estimator's weight rho a_pix / (pi p_r A_T), the
// exact texel areas (the atlas's own shares are off by 10-50% at triangle borders) and the
// interleaved sender, texel by texel.
TEST_F(Atlas, FurnaceTexelsReachTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    std::unique_ptr<Mode> mode = run(s, 1024, {"atlas_resolution=64", "bundle_resolution=256"});
    const FurnaceStats f = furnaceStats(*mode, 2.0);
    std::printf("furnace: %zu texels, area-weighted mean %.5f, worst |L - 2| %.5f\n", f.counted, f.mean, f.worst);
    EXPECT_GT(f.counted, 100u);
    EXPECT_NEAR(f.mean, 2.0, 0.01);
    EXPECT_LT(f.worst, 0.02);
}

// Delayed indirect light ([HHGM10] section 6.4, delay_indirect = N): the first N directions send
// the emitters' light only, and the one-bounce and multi-bounce estimates are summed apart (each
// weighted j^k over its own directions), so the furnace still reaches 2 texel by texel once the
// multi-bounce channel has run: 1 (emission) + 1/2 (one bounce, a plain mean) + 1/2 (the rest of
// the series, j^k from its first direction).
// 64 of 384 directions direct only (48^2 atlas, 192^2 bundles): mean 1.998, worst texel 0.015 off.
// Mutations: the multi-bounce channel normalized by the one-bounce weights of its directions
// (j counted from direction 1) gives 1.689; emitters sent into the multi-bounce channel too, 2.993.
TEST_F(Atlas, FurnaceDelayedIndirectReachesTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    std::unique_ptr<Mode> mode =
        run(s, 384, {"atlas_resolution=48", "bundle_resolution=192", "delay_indirect=64"});
    const FurnaceStats f = furnaceStats(*mode, 2.0);
    std::printf("furnace delay_indirect=64: area-weighted mean %.5f, worst |L - 2| %.5f\n", f.mean, f.worst);
    EXPECT_NEAR(f.mean, 2.0, 0.01);
    EXPECT_LT(f.worst, 0.05);
}

// The furnace seen by the camera: the view raster, the G-buffer's emission and the shade pass's
// texel lookup (bilinear inside charts) give 2 in every pixel.

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
TEST_F(Atlas, FurnaceImageIsTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 32);
    std::unique_ptr<Mode> mode = run(s, 256, {"atlas_resolution=64", "bundle_resolution=256", "view_samples=4"});
    ImageSet out = mode->resolve();
    EXPECT_EQ(out.nonFiniteSamples, 0u);
    double worst = 0.0, mean = 0.0;
    for (const glm::vec3& p : out.radiance().pixels()) {
        worst = std::max(worst, std::abs(double(p.x) - 2.0));
        mean += p.x;
    }
    mean /= double(out.radiance().pixelCount());
    std::printf("furnace image: mean %.5f, worst |L - 2| %.5f\n", mean, worst);
    EXPECT_NEAR(mean, 2.0, 0.02);
    EXPECT_LT(worst, 0.06);
}

// The Cornell box with its area light against the reference path tracer (1024 spp). Five seeds at
// these settings: image mean ratio 0.994 to 1.010 per channel, 8x8-block ratio RMS 0.14 to 0.16 (the
// blotches of 512 directions: each direction lights whole stripes of texels), relMSE 0.020 to
// 0.023. A wrong hemisphere density or texel area moves the mean by 2x; a missing bounce by ~20%.
TEST_F(Atlas, CornellMatchesReference) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", 64);
    std::unique_ptr<Mode> mode = run(s, 512, {"atlas_resolution=256", "bundle_resolution=256", "view_samples=16"});
    ImageSet test = mode->resolve();
    EXPECT_EQ(test.nonFiniteSamples, 0u);
    ImageSet reference = bl::test::renderReference(s, 1024);
    MetricOptions options;
    options.blockSize = 8;
    ImageMetrics m = computeMetrics(test.radiance(), reference.radiance(), options);
    std::printf("cornell: mean ratio %.4f %.4f %.4f  block ratio rms %.4f max %.4f relmse %.5f\n", m.meanRatio.x,
                m.meanRatio.y, m.meanRatio.z, m.blockRatios.rms, m.blockRatios.maxDeviation, m.relMse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 0.02) << "channel " << c;
    EXPECT_LT(m.blockRatios.rms, 0.22);
    EXPECT_LT(m.relMse, 0.035);
}

// A constant white sky over blocks: light enters only where a list ends (the ray leaves the scene).
// The mode is diffuse only, so the glossy block's lobe is removed for both renderers.
TEST_F(Atlas, EnvironmentAtListEndsMatchesReference) {
    Scene s = loadSmall("data/analytic/ao-blocks.toml", 32);
    for (Material& m : s.materials) m.specular = glm::vec3(0.0f);
    std::unique_ptr<Mode> mode = run(s, 512, {"atlas_resolution=256", "bundle_resolution=256", "view_samples=4"});
    ImageSet test = mode->resolve();
    ImageSet reference = bl::test::renderReference(s, 512);
    MetricOptions options;
    options.blockSize = 16;
    ImageMetrics m = computeMetrics(test.radiance(), reference.radiance(), options);
    std::printf("sky: mean ratio %.4f %.4f %.4f  block ratio rms %.4f relmse %.5f\n", m.meanRatio.x, m.meanRatio.y,
                m.meanRatio.z, m.blockRatios.rms, m.relMse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 0.02) << "channel " << c;
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

struct LayerMetrics {
    ImageMetrics all, direct, indirect;
};

// The whole image, layer `direct` (point/spot light reflected once) and the mode's `rest` against
// the reference's indirect1 + indirect2 + rest (8x8 blocks); printed under `label`.
LayerMetrics layerMetrics(const ImageSet& test, const ImageSet& reference, const char* label) {
    MetricOptions options;
    options.blockSize = 8;
    LayerMetrics m{computeMetrics(test.radiance(), reference.radiance(), options),
                   computeMetrics(bl::test::layerOf(test, "direct"), bl::test::layerOf(reference, "direct"), options),
                   computeMetrics(bl::test::layerOf(test, "rest"), sumOf(reference, {"indirect1", "indirect2", "rest"}),
                                  options)};
    std::printf("%s: all %.4f %.4f %.4f (block rms %.4f relmse %.5f), direct %.4f %.4f %.4f, indirect %.4f %.4f %.4f\n",
                label, m.all.meanRatio.x, m.all.meanRatio.y, m.all.meanRatio.z, m.all.blockRatios.rms, m.all.relMse,
                m.direct.meanRatio.x, m.direct.meanRatio.y, m.direct.meanRatio.z, m.indirect.meanRatio.x,
                m.indirect.meanRatio.y, m.indirect.meanRatio.z);
    return m;
}

// Every channel's image mean ratio of the whole image, layer `direct` and the indirect light within
// the given tolerances of 1.
void expectChannelMeans(const LayerMetrics& m, double all, double direct, double indirect) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(m.all.meanRatio[c], 1.0, all) << "channel " << c;
        EXPECT_NEAR(m.direct.meanRatio[c], 1.0, direct) << "channel " << c;
        EXPECT_NEAR(m.indirect.meanRatio[c], 1.0, indirect) << "channel " << c;
    }
}

} // namespace

// The Cornell box lit by a point light only ([HHGM10] section 6.5 hybrid): its light reaches the
// atlas by cube shadow maps averaged over 2x2 points per texel (layer `direct`), the exchange carries
// it on (layer `rest`). Against the reference's layers (512 spp): direct image mean 1.000-1.002,
// whole image 0.989-1.004 over four seeds at 256 directions (relMSE 0.0027-0.0035, 8x8 block ratio
// RMS 0.05-0.08). Without the direct pass nothing is lit; without the exchange the indirect third is
// missing.
TEST_F(Atlas, CornellPointLightMatchesReference) {
    Scene s = loadSmall("data/cornell-box/cornell-point.toml", 64);
    std::unique_ptr<Mode> mode =
        run(s, 256, {"atlas_resolution=256", "bundle_resolution=256", "view_samples=4", "shadow_resolution=512"});
    ImageSet test = mode->resolve();
    EXPECT_EQ(test.nonFiniteSamples, 0u);
    ImageSet reference = bl::test::renderReference(s, 512);
    const LayerMetrics m = layerMetrics(test, reference, "cornell point");
    expectChannelMeans(m, 0.025, 0.015, 0.06);
    EXPECT_LT(m.all.blockRatios.rms, 0.12);
    EXPECT_LT(m.all.relMse, 0.008);
}

// Delayed indirect light on the Cornell box (area light): with delay_indirect the one-bounce
// estimate is light of two segments and goes to layer `direct`, the multi-bounce estimate to
// `rest`, so each is checked against its own reference layer (direct; indirect1 + indirect2 +
// rest). 64 of 384 directions direct only, 32^2 pixels: image 0.998-1.002 per channel, direct
// 1.003-1.012, indirect 1.007-1.010, relMSE 0.012 (0.026 with j^k weights in the one-bounce
// channel too). Mutations: the multi-bounce normalization of
// the furnace test (indirect 0.37-0.43), emitters into the multi-bounce channel too (indirect
// 2.9-3.5), the one-bounce estimate shown in `rest` (direct 0).
TEST_F(Atlas, CornellDelayedIndirectMatchesReferenceLayers) {
    Scene s = loadSmall("data/cornell-box/cornell.toml", 32);
    std::unique_ptr<Mode> mode = run(s, 384, {"atlas_resolution=128", "bundle_resolution=192", "view_samples=16",
                                              "delay_indirect=64"});
    ImageSet test = mode->resolve();
    EXPECT_EQ(test.nonFiniteSamples, 0u);
    ImageSet reference = bl::test::renderReference(s, 1024);
    const LayerMetrics m = layerMetrics(test, reference, "cornell delay_indirect=64");
    expectChannelMeans(m, 0.03, 0.03, 0.05);
    EXPECT_LT(m.all.relMse, 0.05);
}

// McGuire's CornellBox-Glossy with exact Phong lobes (exponent 40 on the sphere and the short box)
// lit by a point light ([HHGM10] sections 5.3-5.4): the glossy transfer atlas carries light through
// the lobes from surface to surface (the box top throws the light's reflection onto the ceiling,
// the sphere reflects the room), the final gather shows the lobes toward the eye, the highlight
// pass the light's own reflection. Against the reference's layers (256 spp); indirect = the
// reference's indirect1 + indirect2 + rest against the mode's `rest`. Seeds 1 / 2 / 3 at these
// settings: image mean 0.997-1.010 / 1.003-1.007 / 0.980-0.993, direct 1.011 (the highlight at
// 32^2), indirect 0.981-1.009 / 0.995-1.004 / 0.941-0.978 (mean of the channels 0.991 / 0.998 /
// 0.957), relMSE 0.012-0.014. Without the glossy transfer (glossy = gather) the image mean falls
// to 0.941-0.951 and the indirect to 0.873-0.885 (channel mean 0.877, seed 2); a mutation dropping
// only the exchange's glossy store (the lights' glossy transfer kept) gives image mean 0.963-0.974
// and indirect channel mean 0.924; with the lobes off (their albedo only, as before) the image mean
// is 0.870-0.880. Tolerances: image mean within 5% per channel, the indirect's channel mean within
// 6% (seed 3's blue is 5.9% low: per channel the seeds spread too far), direct within 4%.
TEST_F(Atlas, GlossyCornellMatchesReference) {
    Scene s = loadSmall("data/external/cornell-glossy-point.toml", 32);
    const std::vector<std::string> settings{"atlas_resolution=128", "bundle_resolution=192", "view_samples=16"};
    ImageSet test = run(s, 512, settings)->resolve();
    EXPECT_EQ(test.nonFiniteSamples, 0u);
    ImageSet reference = bl::test::renderReference(s, 256);
    const auto [all, direct, indirect] = layerMetrics(test, reference, "cornell glossy");
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(all.meanRatio[c], 1.0, 0.05) << "channel " << c;
        EXPECT_NEAR(direct.meanRatio[c], 1.0, 0.04) << "channel " << c;
    }
    EXPECT_NEAR((indirect.meanRatio.x + indirect.meanRatio.y + indirect.meanRatio.z) / 3.0, 1.0, 0.06);
}

// An HDR environment map (classroom sky, a sun in it) over blocks: each direction's escaping rays
// carry the map's radiance along -omega / +omega, one lookup per direction (all rays of a bundle are
// parallel). Directions by environment importance (luminance + the mean as offset), each weighted
// by its density. Glossy lobe removed for both renderers (the mode is diffuse). Four seeds at 512
// directions: image mean ratio 0.967-1.014 (Halton directions: 0.942-1.018), block RMS 0.02-0.05;
// the sun's few directions dominate the spread. Swapping the two escape directions (sky below)
// moves the mean by far more.
TEST_F(Atlas, EnvironmentMapMatchesReference) {
    Scene s = loadSmall("data/analytic/sky-blocks.toml", 32);
    for (Material& m : s.materials) m.specular = glm::vec3(0.0f);
    ImageSet reference = bl::test::renderReference(s, 1024);
    std::unique_ptr<Mode> mode =
        run(s, 512, {"atlas_resolution=256", "bundle_resolution=256", "view_samples=4", "directions=importance"});
    ImageSet test = mode->resolve();
    EXPECT_EQ(test.nonFiniteSamples, 0u);
    MetricOptions options;
    options.blockSize = 8;
    ImageMetrics m = computeMetrics(test.radiance(), reference.radiance(), options);
    std::printf("sky map: mean ratio %.4f %.4f %.4f  block ratio rms %.4f relmse %.5f\n", m.meanRatio.x, m.meanRatio.y,
                m.meanRatio.z, m.blockRatios.rms, m.relMse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 0.05) << "channel " << c;
    EXPECT_LT(m.blockRatios.rms, 0.08);
}

// Bounce-by-bounce transfer with path length limits in the furnace (emission 1, albedo 1/2): at most
// 1, 2, 3 segments give 1, 1.5, 1.75 in every texel (the geometric series cut after 0, 1, 2
// reflections), each pass's sender being exactly the previous pass's light.
TEST_F(Atlas, FurnacePathLengthLimits) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    const double expected[] = {1.0, 1.5, 1.75};
    for (int segments = 1; segments <= 3; ++segments) {
        const std::uint32_t directions = segments == 1 ? 1u : 256u * std::uint32_t(segments - 1);
        std::unique_ptr<Mode> mode =
            run(s, directions,
                {"atlas_resolution=48", "bundle_resolution=192", "transfer=bounce", "bounce_directions=256",
                 "max_segments=" + std::to_string(segments)});
        const FurnaceStats f = furnaceStats(*mode, expected[segments - 1]);
        const double mean = f.mean, worst = f.worst;
        std::printf("furnace max_segments=%d: %u directions, mean %.5f (expected %.2f), worst deviation %.5f\n", segments,
                    directions, mean, expected[segments - 1], worst);
        EXPECT_NEAR(mean, expected[segments - 1], 0.005) << "max_segments " << segments;
        EXPECT_LT(worst, 0.03) << "max_segments " << segments;
    }
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
    const std::vector<std::string> settings{"atlas_resolution=128", "bundle_resolution=128", "view_samples=2"};
    auto passRuns = [&](const Scene& s, const std::string& name) {
        for (const PlannedPass& p : createMode("atlas", settings)->plan(s)) {
            if (p.name == name) return p.runs;
        }
        ADD_FAILURE() << "no pass " << name;
        return false;
    };
    EXPECT_FALSE(passRuns(plain, "shadow maps"));
    EXPECT_TRUE(passRuns(forced, "shadow maps"));
    EXPECT_FALSE(passRuns(plain, "glossy transfer"));
    EXPECT_FALSE(passRuns(plain, "glossy gather"));
    EXPECT_TRUE(passRuns(forced, "glossy transfer"));
    EXPECT_TRUE(passRuns(forced, "glossy gather"));
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
