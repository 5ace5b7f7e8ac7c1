// The surface convention every bundle walk of the path-tracing modes shares (shaders/bundle/
// Traversal.glsl: blBundleSurfaceDepth, blBundleSurfaceNearest), seen through the modes that use it:
// multibounce (every bounce), bidir (the pairs' bundles, the two-bounce term) and skylight
// (visibility). Reflection is two-sided, so the winding of the faces must not change an image; a
// closed wall, however thin, carries no light through it; a face duplicated with the other winding
// changes nothing.
//
// Tolerances. Winding and duplicates: both sides of a comparison use the same seed, so the images
// share their bundle directions and camera samples and differ only by what the change does and by
// float rounding that flips a discrete choice now and then. Paired ratios measured at these
// settings (seeds 1..4, every face flipped / every mesh duplicated reversed, in memory and as OBJ
// files whose quads then split along the other diagonal): multibounce within 0.6%, bidir 0.06%,
// skylight 0.000% (the in-memory flip: 0 in every mode); the image means' own spread over seeds is
// 1.4% / 4.3% / 6.3%. The bound 1% is about 4 paired standard deviations of the worst mode
// (multibounce, ~0.25%); the face-bit walk gave
// flipped 0.68 / 0.92 / 0.67 and duplicated 0.80 / 0.91 / 0.65. Light leak: issue 19 asks for the
// dark side below 1% of the lit side at the default settings (the face-bit walk: 38% multibounce;
// two quads 49% multibounce, 16% bidir with the quads facing into the gap).
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <cstdio>

using namespace bl;

namespace {

constexpr int kResolution = 32;

class SurfaceConvention : public bl::test::VulkanTest {
public:
    glm::dvec3 renderMean(const std::string& mode, const Scene& scene, std::uint32_t iterations,
                          const std::vector<std::string>& settings = {}, std::uint64_t seed = 1) {
        std::unique_ptr<Mode> m = createMode(mode, settings);
        m->setScene(scene, &ctx());
        for (std::uint32_t i = 0; i < iterations; ++i) {
            m->iterate({i, seed, 0.0});
        }
        ImageSet out = m->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        EXPECT_EQ(out.radiance().countNonFinite(), 0u);
        return out.radiance().mean();
    }
};

Scene load(const std::string& path) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {kResolution, kResolution};
    return s;
}

// Every triangle wound the other way and its vertex normals turned with it, as a file written the
// other way round (with or without vn) would load.
void flipWinding(Mesh& m) {
    for (glm::uvec3& t : m.triangles) std::swap(t.y, t.z);
    for (glm::vec3& n : m.normals) n = -n;
}

Scene flipped(Scene s) {
    for (Mesh& m : s.meshes) flipWinding(m);
    return s;
}

// Every mesh twice, the copy wound the other way (coincident faces of opposite winding).
Scene withReversedDuplicates(Scene s) {
    const std::size_t count = s.meshes.size();
    for (std::size_t i = 0; i < count; ++i) {
        Mesh copy = s.meshes[i];
        copy.name += ":reversed";
        flipWinding(copy);
        s.meshes.push_back(copy);
    }
    return s;
}

// The point-lit Cornell box under a constant white sky (no point light): skylight's scene.
Scene skyBox() {
    Scene s = load("data/cornell-box/cornell-point.toml");
    s.lights.clear();
    s.environment.present = true;
    s.environment.radiance = glm::vec3(1.0f);
    return s;
}

void expectSameMean(const glm::dvec3& changed, const glm::dvec3& original, double tolerance, const char* what) {
    for (int c = 0; c < 3; ++c) {
        const double ratio = changed[c] / original[c];
        std::printf("%s channel %d: %.6g / %.6g = %.5f\n", what, c, changed[c], original[c], ratio);
        EXPECT_NEAR(ratio, 1.0, tolerance) << what << ", channel " << c;
    }
}

struct ModeCase {
    const char* mode;
    std::uint32_t iterations;
    double tolerance; // on the paired ratio of image means (see above)
};

// Settings of the winding and duplicate checks: the modes' defaults, few iterations.
const ModeCase kMultibounce{"multibounce", 2, 0.01};
const ModeCase kBidir{"bidir", 2, 0.01};
const ModeCase kSkylight{"skylight", 16, 0.01};

} // namespace

TEST_F(SurfaceConvention, FlippedWindingChangesNoImage) {
    const Scene box = load("data/cornell-box/cornell-point.toml");
    const Scene sky = skyBox();
    for (const ModeCase& c : {kMultibounce, kBidir, kSkylight}) {
        const Scene& s = std::string(c.mode) == "skylight" ? sky : box;
        expectSameMean(renderMean(c.mode, flipped(s), c.iterations), renderMean(c.mode, s, c.iterations), c.tolerance,
                       c.mode);
    }
}

TEST_F(SurfaceConvention, ReversedDuplicateFacesChangeNoImage) {
    const Scene box = load("data/cornell-box/cornell-point.toml");
    const Scene sky = skyBox();
    for (const ModeCase& c : {kMultibounce, kBidir, kSkylight}) {
        const Scene& s = std::string(c.mode) == "skylight" ? sky : box;
        expectSameMean(renderMean(c.mode, withReversedDuplicates(s), c.iterations), renderMean(c.mode, s, c.iterations),
                       c.tolerance, c.mode);
    }
}

namespace {

// light-leak.toml's room, its wall replaced by `wall` (none: keep the file's closed 1e-3 box).
Scene leakScene(const std::vector<Mesh>& wall) {
    Scene s = load("data/analytic/light-leak.toml");
    if (!wall.empty()) {
        std::erase_if(s.meshes, [](const Mesh& m) { return m.name.find("thin-wall") != std::string::npos; });
        for (const Mesh& m : wall) s.meshes.push_back(m);
    }
    return s;
}

// A unit quad in the plane x = `at`, its front facing +x (`facing` = +1) or -x.
Mesh quadAt(float at, float facing, std::uint32_t material) {
    Mesh m;
    m.name = "quad";
    m.positions = {{at, 0, 0}, {at, 1, 0}, {at, 1, 1}, {at, 0, 1}};
    m.normals.assign(4, glm::vec3(1, 0, 0));
    m.triangles = {{0, 1, 2}, {0, 2, 3}}; // counter-clockwise seen from +x: the front faces +x
    m.material = material;
    if (facing < 0.0f) flipWinding(m);
    return m;
}

// Two single quads 1e-4 apart at x = 0.5, both facing out of the wall or both into the gap.
std::vector<Mesh> twoQuads(bool facingOut, std::uint32_t material) {
    const float out = facingOut ? 1.0f : -1.0f;
    return {quadAt(0.5f + 5e-5f, out, material), quadAt(0.5f - 5e-5f, -out, material)};
}

// The camera's room, lit by the light as the file places it (beyond the wall), against the same
// room with the light mirrored into it: the fraction of the lit side's light that leaks.
double leakFraction(SurfaceConvention& t, const std::string& mode, const Scene& dark, std::uint32_t iterations) {
    Scene lit = dark;
    lit.lights.at(0).position.x = 1.0f - lit.lights.at(0).position.x;
    const glm::dvec3 d = t.renderMean(mode, dark, iterations);
    const glm::dvec3 l = t.renderMean(mode, lit, iterations);
    std::printf("%s: dark side %.6g, lit side %.6g: %.4f%%\n", mode.c_str(), d.x, l.x, 100.0 * d.x / l.x);
    return d.x / l.x;
}

} // namespace

// light-leak.toml must be black: its wall is a closed box 1e-3 of the room thick. Also two single
// quads 1e-4 apart, wound either way.
TEST_F(SurfaceConvention, ThinWallsKeepTheDarkSideBlack) {
    const std::uint32_t white = 0;
    const std::vector<std::pair<const char*, Scene>> walls{{"closed wall 1e-3", leakScene({})},
                                                           {"two quads facing out", leakScene(twoQuads(true, white))},
                                                           {"two quads facing in", leakScene(twoQuads(false, white))}};
    for (const char* mode : {"multibounce", "bidir"}) {
        for (const auto& [name, scene] : walls) {
            EXPECT_LT(leakFraction(*this, mode, scene, 2), 0.01) << mode << ", " << name;
        }
    }
}
