// Issue 19, far coordinates: a scene far from the origin is moved near it on loading (its offset
// kept in double), and what float cannot represent is refused with the value named.
#include "scene/ScenePrecision.h"
#include "base/Error.h"
#include "scene/SceneLoader.h"
#include "support/MovedScenes.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>
#include <limits>

using namespace bl;
using bl::test::errorOf;
using bl::test::writeMovedScene;

namespace {
const char* kBox = "data/cornell-box/cornell-point.toml";
}

TEST(ScenePrecision, NearSceneKeepsItsCoordinates) {
    // The Cornell box's centre lies inside its bounding sphere: nothing to gain, nothing moves.
    const Scene s = loadScene(bl::test::sourcePath(kBox));
    EXPECT_EQ(s.origin, glm::dvec3(0.0));
    EXPECT_EQ(s.lights.at(0).position, glm::vec3(278.0f, 500.0f, 279.5f));
}

TEST(ScenePrecision, FarSceneIsRecentredWithItsOffsetInDouble) {
    const Scene near = loadScene(bl::test::sourcePath(kBox));
    const glm::dvec3 offset(1e6, -2e6, 3e6);
    const Scene far = loadScene(writeMovedScene(kBox, offset));
    const Bounds b = near.bounds();
    const glm::dvec3 centre = 0.5 * (glm::dvec3(b.lo) + glm::dvec3(b.hi));
    // The loader bakes the file's translate in float: every vertex carries up to half a float step
    // at 3e6 (0.125), the only error; re-centring itself is exact.
    const double step = 0.25;
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(far.origin[i], offset[i] + centre[i], step) << i;
    }
    const Bounds fb = far.bounds();
    EXPECT_LT(glm::length(0.5f * (fb.lo + fb.hi)), 1.0f); // centred
    ASSERT_EQ(far.meshes.size(), near.meshes.size());
    // Every far vertex lies where a near vertex lies, moved. Compared as sets of positions: flat
    // normals are generated from the far floats before re-centring, so two coplanar faces' normals
    // can differ by rounding and a vertex they share near the origin may be split in the far copy.
    double worst = 0.0;
    for (std::size_t m = 0; m < near.meshes.size(); ++m) {
        ASSERT_FALSE(far.meshes[m].positions.empty()) << m;
        for (const glm::vec3& p : far.meshes[m].positions) {
            const glm::dvec3 world = far.origin + glm::dvec3(p);
            double nearest = std::numeric_limits<double>::infinity();
            for (const glm::vec3& q : near.meshes[m].positions) {
                nearest = std::min(nearest, glm::length(world - (glm::dvec3(q) + offset)));
            }
            worst = std::max(worst, nearest);
        }
    }
    EXPECT_LE(worst, step);
    // Lights and camera move with it, exactly (the file's numbers are floats at 1e6).
    const glm::dvec3 light = far.origin + glm::dvec3(far.lights.at(0).position);
    EXPECT_NEAR(glm::length(light - (glm::dvec3(278.0, 500.0, 279.5) + offset)), 0.0, step);
    const glm::dvec3 eye = far.origin + glm::dvec3(far.camera.pose.position);
    EXPECT_NEAR(glm::length(eye - (glm::dvec3(278.0, 273.0, -800.0) + offset)), 0.0, step);
    EXPECT_NE(far.features().describe().find("origin"), std::string::npos);
}

TEST(ScenePrecision, RefusesGeometryTooFarForItsSize) {
    // 1e8 mm out, float steps by 8 mm: the 966 mm box keeps 6.9 bits, below kMinResolvedBits.
    const std::string e =
        errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(1e8, 0.0, 0.0))); });
    EXPECT_NE(e.find("float coordinates step by 8"), std::string::npos) << e;
    EXPECT_NE(e.find("lies 100000560 from the origin"), std::string::npos) << e;
    // 4e6 keeps 10.9 bits: loaded (and re-centred).
    EXPECT_EQ(errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(4e6, 0.0, 0.0))); }), "");
}

TEST(ScenePrecision, RefusesCoordinatesFloatCannotSquare) {
    // Scaled by 1e7 (the issue's case: the reference rendered black), the box's coordinates reach
    // 5.6e9: its squared areas overflow float.
    const std::string e = errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(0.0), 1e7)); });
    EXPECT_NE(e.find("mesh '"), std::string::npos) << e;
    EXPECT_NE(e.find("not representable"), std::string::npos) << e;
    EXPECT_NE(e.find("moved.toml"), std::string::npos) << e; // the file
    // A light too far away, named as such.
    const std::string path = bl::test::writeTempFile("light.toml", R"(
[[mesh]]
file = ")" + bl::test::sourcePath("data/cornell-box/meshes/floor.obj") +
                                                                       R"("
[[light]]
position = [0.0, 3e10, 0.0]
intensity = [1.0, 1.0, 1.0]
)");
    const std::string l = errorOf([&] { loadScene(path); });
    EXPECT_NE(l.find("light 1 position (0, 3e+10, 0)"), std::string::npos) << l;
}

TEST(ScenePrecision, RefusesAnExtentFloatCannotResolve) {
    // Scaled by 1e-10 the box spans 9.7e-8, below kMinDiameter.
    const std::string e = errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(0.0), 1e-10)); });
    EXPECT_NE(e.find("the geometry spans"), std::string::npos) << e;
    // 1e-6 and 1e6 are fine.
    EXPECT_EQ(errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(0.0), 1e-6)); }), "");
    EXPECT_EQ(errorOf([] { loadScene(writeMovedScene(kBox, glm::dvec3(0.0), 1e6)); }), "");
}
