// The criteria of modes/SettingTrades.h on scenes whose answer is known: a plane has nothing a
// shadow cube or a bundle can get wrong; a small box on it has creases and an outline that coarse
// settings cannot resolve, and fine ones can. Host code only (Embree), no device.
#include "modes/SettingTrades.h"
#include "modes/Mode.h"
#include "modes/Registry.h"
#include "reference/EmbreeScene.h"
#include "reference/ReferenceRenderer.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

using namespace bl;

namespace {

// An axis-aligned box [lo, hi], faces outward (counter-clockwise seen from outside).
Mesh makeBox(glm::vec3 lo, glm::vec3 hi, std::uint32_t material) {
    Mesh m;
    m.name = "box";
    auto corner = [&](int i) {
        return glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    };
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) { // four vertices of its own per face: flat normals
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        const glm::vec3 n =
            glm::normalize(glm::cross(corner(q[1]) - corner(q[0]), corner(q[2]) - corner(q[0])));
        for (int c : q) {
            m.positions.push_back(corner(c));
            m.normals.push_back(n);
        }
        m.triangles.push_back({base, base + 1, base + 2});
        m.triangles.push_back({base, base + 2, base + 3});
    }
    m.material = material;
    return m;
}

// pointLightOverPlane (h = 1, a 8 x 8 floor) with a box of side `side` on the floor beside the
// light's foot, the camera looking at the box.
Scene boxOnPlane(float side) {
    Scene s = test::pointLightOverPlane(0.5f, 1.0f, 1.0f, 64);
    s.meshes.push_back(
        makeBox(glm::vec3(0.2f, 0.0f, 0.2f), glm::vec3(0.2f + side, side, 0.2f + side), 0));
    s.camera.pose.target = glm::vec3(0.2f + 0.5f * side, 0.0f, 0.2f + 0.5f * side);
    s.camera.pose.position = s.camera.pose.target + glm::vec3(0.5f, 1.5f, 1.0f) * (2.0f * side);
    return s;
}

} // namespace

TEST(SettingTrades, PlaneHasNothingToTrade) {
    const Scene s = test::pointLightOverPlane(0.5f, 1.0f, 1.0f, 64);
    const EmbreeScene rt(s, 0.0);
    const std::vector<ViewPoint> points = viewPoints(rt, s, 32);
    ASSERT_GT(points.size(), 500u);
    // A planar receiver never shadows itself (receiver-plane test), and a bundle's fragments of
    // x's own plane cross x's ray at x: both exact at any resolution.
    for (std::uint32_t r : {8u, 512u}) {
        EXPECT_EQ(shadowCubeError(rt, points, 0, r).error, 0.0) << r;
        // (to float rounding of the replay's depths at grazing directions)
        EXPECT_LT(std::abs(bundleVisibilityError(rt, points, r, false, 2).error),
                  0.2 * kTradeTolerance)
            << r;
    }
}

TEST(SettingTrades, ShadowCubeErrorShrinksWithResolution) {
    const Scene s = boxOnPlane(0.5f);
    const EmbreeScene rt(s, 0.0);
    const std::vector<ViewPoint> points = viewPoints(rt, s, 48);
    const TradeError coarse = shadowCubeError(rt, points, 0, 8);
    const TradeError fine = shadowCubeError(rt, points, 0, 2048);
    EXPECT_TRUE(coarse.exceeds()) << coarse.error << " +- " << coarse.stderr_;
    EXPECT_TRUE(fine.within()) << fine.error;
    EXPECT_LT(std::abs(fine.error), std::abs(coarse.error));
}

TEST(SettingTrades, BundlePixelMustResolveTheObjectsInView) {
    // A 5 cm box on an 8 m floor: the floor sets the sphere, so a 64^2 bundle's pixel (18 cm)
    // is larger than the box (36 cm at 32^2); fitted to what the camera sees (about 1 m) it is 1.6
    // cm.
    const Scene s = boxOnPlane(0.05f);
    const EmbreeScene rt(s, 0.0);
    const std::vector<ViewPoint> points = viewPoints(rt, s, 48);
    const TradeError sphere = bundleVisibilityError(rt, points, 32, false, 4);
    const TradeError visible = bundleVisibilityError(rt, points, 512, true, 4);
    EXPECT_TRUE(sphere.exceeds()) << sphere.error << " +- " << sphere.stderr_;
    EXPECT_TRUE(visible.within()) << visible.error << " +- " << visible.stderr_;
}

TEST(SettingTrades, ModesWarnWithTheSettingThatFixesIt) {
    Scene s = boxOnPlane(0.5f);
    const std::vector<std::string> coarse =
        settingTrades(*createMode("raster", {"shadow_resolution=16"}), s);
    bool shadowFix = false;
    for (const std::string& w : coarse) {
        shadowFix = shadowFix || w.find("fix: shadow_resolution=") != std::string::npos;
    }
    EXPECT_TRUE(shadowFix);

    EXPECT_TRUE(settingTrades(*createMode("raster", {"shadow_resolution=2048"}), s).empty());
    // The reference evaluates in its own precision and has no cubes or bundles: nothing to say.
    EXPECT_TRUE(settingTrades(*createMode("reference", {}), s).empty());
}

// Raster's environment directions answer visibility from depth maps over the scene's bounding
// sphere by skylight's rule: the 5 cm box on the 8 m floor under a constant sky is misjudged at
// 32^2 maps and said, naming the maps and their setting; fine maps, no environment light
// (environment_shots = 0) or no sky say nothing about them. (Before this check raster read the
// env-lit bunny 6 % dark without a word.)
TEST(SettingTrades, RasterSaysWhenItsEnvironmentMapsAreTooCoarse) {
    Scene s = boxOnPlane(0.05f);
    s.lights.clear();
    s.environment.present = true;
    s.environment.radiance = glm::vec3(1.0f);
    auto says = [&](const Scene& scene, std::vector<std::string> settings) {
        settings.push_back("shadow_resolution=2048");
        for (const std::string& w : settingTrades(*createMode("raster", settings), scene))
            if (w.find("environment depth maps of") != std::string::npos) return w;
        return std::string();
    };
    const std::string coarse = says(s, {"environment_shadow_resolution=32"});
    EXPECT_NE(coarse.find("environment depth maps of 32^2 pixels over the scene's bounding sphere"), std::string::npos)
        << coarse;
    EXPECT_NE(coarse.find("environment_shadow_resolution="), std::string::npos) << coarse;
    EXPECT_EQ(coarse.find("fit="), std::string::npos) << coarse; // raster has no fit to offer
    EXPECT_EQ(says(s, {"environment_shadow_resolution=2048"}), "");
    EXPECT_EQ(says(s, {"environment_shadow_resolution=32", "environment_shots=0"}), "");
    Scene plane = test::pointLightOverPlane(0.5f, 1.0f, 1.0f, 64);
    plane.lights.clear();
    plane.environment = s.environment;
    EXPECT_EQ(says(plane, {"environment_shadow_resolution=32"}), ""); // a plane has nothing to misjudge
    Scene dark = boxOnPlane(0.05f);
    EXPECT_EQ(says(dark, {"environment_shadow_resolution=32"}), ""); // no sky
}

// Skylight's bundles are walked by their facets' planes with the near end's contact taps; on a
// flat-shaded heightfield whose facets are 2-4 px at 64^2 the taps find creases that are not a
// room's, and the check, which replays them, says so (-4.5 %, as the images read:
// Skylight.CurvedAndRoughMeshesUnderASkyReadWhatTheCheckPredicts) with a setting that fixes it;
// at that setting it is quiet.
TEST(SettingTrades, SkylightSaysWhereItsPixelsAreCoarseForTheFacets) {
    const Scene s = test::bumpsUnderSky(24, 0.03f, 32);
    auto says = [&](std::vector<std::string> settings) {
        for (const std::string& w : settingTrades(*createMode("skylight", settings), s))
            if (w.find("misjudge the visibility") != std::string::npos) return w;
        return std::string();
    };
    const std::string coarse = says({"bundle_resolution=64"});
    const std::size_t fix = coarse.find("fix: ");
    ASSERT_NE(fix, std::string::npos) << coarse;
    std::vector<std::string> fixed{"bundle_resolution=64"};
    std::istringstream words(coarse.substr(fix + 5, coarse.find(" (", fix) - fix - 5));
    for (std::string w; words >> w;) {
        if (w.rfind("bundle_resolution=", 0) == 0) fixed[0] = w;
        else fixed.push_back(w);
    }
    EXPECT_EQ(says(fixed), "") << coarse;
}

// Skylight with glossy_control_variate = off meets a glossy lobe only through its uniform bundle
// directions, once per e + 1 of them: a lobe past a long run's 1024 directions is said, with the
// material; a broad one is not; with the default (on) each pixel samples the lobe: nothing to say.
TEST(SettingTrades, SkylightSaysWhenALobeIsNarrowerThanItsDirections) {
    EXPECT_DOUBLE_EQ(directionsPerLobeHit(1e4), 10001.0);
    Scene s = boxOnPlane(0.5f);
    s.materials[0].specular = glm::vec3(0.5f);
    s.materials[0].exponentU = s.materials[0].exponentV = 1e4f;
    bool said = false;
    for (const std::string& w : settingTrades(*createMode("skylight", {"bundle_resolution=2048", "fit=visible", "glossy_control_variate=off"}), s)) {
        said = said || (w.find("glossy exponent of 10000") != std::string::npos && w.find("10001") != std::string::npos);
    }
    EXPECT_TRUE(said);
    s.materials[0].exponentU = s.materials[0].exponentV = 100.0f;
    for (const std::string& w : settingTrades(*createMode("skylight", {"bundle_resolution=2048", "fit=visible", "glossy_control_variate=off"}), s)) {
        EXPECT_EQ(w.find("glossy exponent"), std::string::npos) << w;
    }
    s.materials[0].exponentU = s.materials[0].exponentV = 1e4f;
    for (const std::string& w : settingTrades(*createMode("skylight", {"bundle_resolution=2048", "fit=visible"}), s)) {
        EXPECT_EQ(w.find("glossy exponent"), std::string::npos) << w; // the default samples the lobe
    }
    for (const std::string& w : settingTrades(*createMode("raster", {"shadow_resolution=2048"}), s)) {
        EXPECT_EQ(w.find("glossy exponent"), std::string::npos) << w; // raster evaluates the lobe itself
    }
}

// Multibounce with K <= 8 bundles ends a path after K + 2 segments (each bundle once per path).
// The check's estimate of what the cut leaves out agrees with an independent one (other seed, 4x
// the samples) within three combined standard errors; K = 2 on the point-lit Cornell box warns
// (about -10 %) with the smallest K that brings it under 1 %, on the area-lit box with the cut of
// paths that end on the emitter (K + 1 = 3 segments), and K = 16 (no cut) says nothing about paths.
TEST(SettingTrades, MultibounceSaysWhatSmallBundleCountsCut) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    const std::vector<TradeError> e = cutPathErrors(s, {4});
    ASSERT_EQ(e.size(), 1u);
    EXPECT_LT(e[0].error, -0.05);

    Scene small = s;
    small.camera.resolution = {kCutPathWidth, kCutPathWidth};
    auto total = [&](int maxSegments, double& variance) {
        ReferenceSettings settings;
        settings.path.maxSegments = maxSegments;
        ReferenceRenderer r(small, 0.0, settings);
        for (std::uint32_t i = 0; i < 4 * kCutPathSamples; ++i) r.renderPass(i, 12345u);
        double sum = 0.0;
        const Image mean = r.mean();
        for (const glm::vec3& p : mean.pixels()) sum += double(p.x + p.y + p.z);
        const Image v = r.varianceOfMean();
        for (const glm::vec3& p : v.pixels()) variance += double(p.x + p.y + p.z);
        return sum;
    };
    double varianceFull = 0.0, varianceCut = 0.0;
    const double full = total(64, varianceFull);
    const double cut = total(4, varianceCut);
    const double independent = cut / full - 1.0;
    const double stderrIndependent = std::sqrt(varianceFull + varianceCut) / full; // independent halves: conservative
    std::printf("cut at 4 segments: check %.4f +- %.4f, independent %.4f +- %.4f\n", e[0].error, e[0].stderr_, independent,
                stderrIndependent);
    EXPECT_NEAR(e[0].error, independent, 3.0 * std::hypot(e[0].stderr_, stderrIndependent));

    bool said = false;
    for (const std::string& w : settingTrades(*createMode("multibounce", {"bundle_count=2", "directions=random"}), s)) {
        said = said || (w.find("bundle_count=2 ends every path after 4 segments") != std::string::npos &&
                        w.find("fix: bundle_count=") != std::string::npos);
    }
    EXPECT_TRUE(said);
    const Scene area = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    said = false;
    for (const std::string& w :
         settingTrades(*createMode("multibounce", {"bundle_count=2", "emitter_sampling=bundles"}), area)) {
        said = said || w.find("bundle_count=2 ends every path after 3 segments where it meets an emitter (4 with") !=
                           std::string::npos;
    }
    EXPECT_TRUE(said);
    // Emitter points light the last vertex too (mis, the default): emitters' paths end with the
    // point lights', after K + 2.
    said = false;
    for (const std::string& w : settingTrades(*createMode("multibounce", {"bundle_count=2"}), area)) {
        EXPECT_EQ(w.find("where it meets an emitter"), std::string::npos) << w;
        said = said || w.find("bundle_count=2 ends every path after 4 segments") != std::string::npos;
    }
    EXPECT_TRUE(said);
    for (const std::string& w : settingTrades(*createMode("multibounce", {"bundle_count=16"}), s)) {
        EXPECT_EQ(w.find("ends every path"), std::string::npos) << w;
    }
}
