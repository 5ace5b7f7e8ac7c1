// Mode multibounce with textured albedo and imperfect bundles ([TO12p]) against the reference:
// textures beyond the camera's first vertex (perfect bundles' payload UV, imperfect bundles' UV over
// each splat), imperfect bundles' bias bound, and texture detail below the splat size. Shared
// fixture and bounds: MultibounceTestSupport.h.
#include "modes/multibounce/MultibounceTestSupport.h"
#include "modes/multibounce/SplatCoverage.h"
#include "support/TexturedScenes.h"

using namespace bl;
using namespace bl::test::multibounce;

namespace {

// The point-lit box, its floor red where u < 1/2 and green beyond (almost no blue), the light
// lowered to 100 mm above the floor beside the blocks (clear of both), so that the floor is what sends most
// of the indirect light: a floor shaded white (untextured) beyond the camera's first vertex would
// put indirect1's blue channel far off (the texture's blue is 1/100 of the white's).
Scene redGreenFloorBox(int resolution) {
    Scene s = loadSmall("data/cornell-box/cornell-point.toml", resolution);
    EXPECT_TRUE(bl::test::texturePlanar(s, "floor", bl::test::redGreenTexture())) << "no floor mesh";
    s.lights.at(0).position = glm::vec3(420.0f, 100.0f, 120.0f);
    return s;
}

double channelMean(const Image& image, int channel) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += p[channel];
    return sum / double(image.pixelCount());
}

// Each channel's seeds' mean of a layer within `tolerance` (relative) of the reference's channel
// mean: the three checks share the family-wise rate alpha (Bonferroni).
void expectChannelMeans(const std::vector<ImageSet>& runs, const ImageSet& reference, const std::string& name,
                        double tolerance, const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        std::vector<double> means;
        for (const ImageSet& r : runs) means.push_back(channelMean(layer(r, name), c));
        const stats::Summary s = stats::summarize(means);
        const double ref = channelMean(layer(reference, name), c);
        const std::string label = what + " " + (name.empty() ? "radiance" : name) + " channel " + std::to_string(c);
        std::printf("%s: %.5f +- %.5f (stderr), reference %.5f: %+.2f%% (tolerance %.2f%%)\n", label.c_str(), s.mean,
                    s.stderr_, ref, 100.0 * (s.mean / ref - 1.0), 100.0 * tolerance);
        EXPECT_TRUE(stats::agrees(s, ref, tolerance * ref, label, stats::kAlpha / 3.0));
    }
}

// Imperfect bundles' bias per bundle segment: the pixel-centre ray's (f, as for perfect bundles)
// plus d, the share of segments whose end the splats move (a hole: the ray passes through a
// surface; a splat reaching past an edge: it stops where no surface is), measured on the geometry
// alone (SplatCoverage.h: 16 directions at the mode's settings against perfect bundles of the same
// frames). An empirical bound, not a derived one: it takes a moved segment to lose or substitute
// at most its own path's light, which holds for losses but not for a hole that shows a brighter
// surface behind, and d counts segments, not light.
double imperfectSegmentBound(const vk::Context& ctx, const Scene& s, double splatScale, std::uint32_t points) {
    const double f = bundleMisassignment(s, kBundleResolution);
    const double d =
        bl::test::measureSplatCoverage(ctx, s, {splatScale}, 16, points, kBundleResolution).front().segmentsChanged;
    std::printf("imperfect bundles: splat_scale %.2f, %u points: segments moved d = %.4f, bound f + d = %.4f\n",
                splatScale, points, d, f + d);
    return f + d;
}

} // namespace

// Imperfect bundles ([TO12p]) with textured albedo: every bundle of 16384 splats of its own point
// set (splat_scale 2, the defaults), on the point-lit box with the red/green floor; the reference
// looks the texture up at every vertex, the imperfect bundles at the UV over each splat where a path
// meets it. Direct light comes from the shadow cubes (kShadowTolerance), each later bounce through
// one more imperfect bundle segment (imperfectSegmentBound per segment), every channel on its own
// (the texture's red and green, and the blue it lacks). Four seeds: indirect1 -1.6 / -1.4 / +5.3%
// per channel (bound 8.4%: d = 4.0% of segments moved). Mutations (both fail): splat_scale 1 (35%
// holes): indirect1 -35%; the material's white albedo at bundle hits: red +71%, blue +168%.
TEST_F(Multibounce, ImperfectBundlesWithTexturedAlbedoMatchReference) {
    const Scene s = redGreenFloorBox(kStatResolution);
    const double b = imperfectSegmentBound(ctx(), s, 2.0, 16384);
    const std::vector<ImageSet> runs =
        renderSeeds(s, 8, {"paths_per_pixel=32", "bundle_count=16", "bundles=imperfect"}, kTextureSeeds);
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    const std::vector<std::pair<std::string, double>> bounds{{"direct", kShadowTolerance},
                                                             {"indirect1", kShadowTolerance + b},
                                                             {"indirect2", kShadowTolerance + 2 * b},
                                                             {"rest", kShadowTolerance + kRestSegments * b}};
    expectChannelMeans(runs, reference, "direct", kShadowTolerance, "imperfect");
    expectChannelMeans(runs, reference, "indirect1", kShadowTolerance + b, "imperfect");
    expectLayerMean(runs, reference, "", imageTolerance(reference, bounds), "imperfect");
}

// Textured albedo beyond the camera's first vertex with perfect bundles: every vertex looks the
// floor's texture up at the bundle payload's UV in the packed texture buffer. indirect1 (one bundle
// segment) per channel within kShadowTolerance + f. Four seeds: -1.0 / -0.7 / +0.4%. Mutation: the
// material's white albedo at bundle hits (as before the packed texture buffer): red +74%, blue +170%.
TEST_F(Multibounce, PerfectBundlesKeepTexturedAlbedo) {
    const Scene s = redGreenFloorBox(kStatResolution);
    const double f = bundleMisassignment(s, kBundleResolution);
    const std::vector<ImageSet> runs = renderSeeds(s, 8, {"paths_per_pixel=32"}, kTextureSeeds);
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    expectChannelMeans(runs, reference, "indirect1", kShadowTolerance + f, "textured");
}

// Texture detail below the splat size ([TO12p]: texture coordinates at each splat corner). The
// point light hangs 20 mm above the floor between the blocks and the back wall, over a black disc of radius 30 mm in a white
// floor texture: 44% of the floor's irradiance falls on the disc. Splats of 1024 points per
// direction have radius 47 mm, larger than the disc, so the texel at a splat's centre (splat_uv =
// centre) blurs the disc away where the light is brightest and returns far too much light from the
// floor; the UV interpolated over the splat (corners) keeps the disc. Four seeds: corners -5.3% of
// the reference (bound 15.2%: f + d with d = 10.8% of segments moved by splats this large),
// centre +21% over corners (paired).
TEST_F(Multibounce, SplatCornerUvsKeepTextureDetailBelowTheSplatSize) {
    Scene s = loadSmall("data/cornell-box/cornell-point.toml", 32);
    constexpr int kSide = 256;
    Rgba8Image texture{kSide, kSide, std::vector<unsigned char>(kSide * kSide * 4, 255)};
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Mesh& m : s.meshes) {
        if (m.name.find("floor") == std::string::npos) continue;
        for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const glm::vec2 foot(lo.x + 140.0f, lo.z + 420.0f); // 140 mm or more from the walls and blocks
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            // Texel centre on the floor (row 0 is v = 1: OBJ coordinates run upward).
            const glm::vec2 at(lo.x + (x + 0.5f) / kSide * (hi.x - lo.x), lo.z + (1.0f - (y + 0.5f) / kSide) * (hi.z - lo.z));
            unsigned char* t = &texture.texels[std::size_t(4 * (y * kSide + x))];
            const unsigned char value = glm::length(at - foot) < 30.0f ? 0 : 220;
            t[0] = t[1] = t[2] = value;
        }
    }
    ASSERT_TRUE(bl::test::texturePlanar(s, "floor", texture)) << "no floor mesh";
    s.lights.at(0).position = glm::vec3(foot.x, lo.y + 20.0f, foot.y);
    const ImageSet reference = bl::test::renderReference(s, kReferenceSpp);
    const double bound = kShadowTolerance + imperfectSegmentBound(ctx(), s, 2.0, 1024);
    const std::vector<std::string> common{"paths_per_pixel=32", "bundle_count=16", "bundles=imperfect", "points=1024"};
    std::vector<std::string> corners = common, centre = common;
    corners.push_back("splat_uv=corners");
    centre.push_back("splat_uv=centre");
    // Corners: indirect1 (one imperfect segment) within its bound. Centre: the same frames and points
    // (same seeds, so the splats' geometric error is common to both and cancels in the paired
    // difference), brighter than corners beyond the seeds' noise, as the blurred disc predicts.
    const std::vector<ImageSet> withCorners = renderSeeds(s, 8, corners, kTextureSeeds);
    expectLayerMean(withCorners, reference, "indirect1", bound, "splat_uv=corners");
    const std::vector<ImageSet> withCentre = renderSeeds(s, 8, centre, kTextureSeeds);
    std::vector<double> cornerMeans, centreMeans;
    for (const ImageSet& r : withCorners) cornerMeans.push_back(imageMean(layer(r, "indirect1")));
    for (const ImageSet& r : withCentre) centreMeans.push_back(imageMean(layer(r, "indirect1")));
    const stats::Summary d = stats::pairedDifference(centreMeans, cornerMeans);
    const double brighter = d.mean / stats::summarize(cornerMeans).mean;
    std::printf("splat_uv=centre - corners, indirect1: %+.5f +- %.5f (%+.1f%%)\n", d.mean, d.stderr_, 100.0 * brighter);
    // One-sided (the geometry predicts the sign): t(1 - alpha, n - 1).
    EXPECT_GT(d.mean, stats::studentTCritical(2.0 * stats::kAlpha, double(d.n - 1)) * d.stderr_)
        << "splat_uv=centre is not brighter than corners: the test cannot tell the corners' UVs from the centre's";
}

