// Measurements behind experiments/bidir-b3/ (not a test: disabled, run by
// experiments/bidir-b3/run.sh with --gtest_also_run_disabled_tests). Issue 19's B3: do bidir's
// VPL strategy and bundle strategy estimate the same one-bounce integral on a smooth mesh?
// The glossy Cornell box (data/external/cornell-glossy-point.toml), 32^2, 4 x 4 regions of
// 8 x 8 pixels, indirect1 of strategy = vpl (traced VPLs) and strategy = bundle, bounces = 1,
// suppression = none, S seeds x F frames each, paired by seed; once with the sphere's vertex
// normals and once with its faces shaded flat (each triangle its own vertices, the face normal).
// Prints per region both strategies' means, their paired difference with its standard error,
// and the reference path tracer's value.
#include "modes/Registry.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cstdio>
#include <cstdlib>

using namespace bl;
namespace stats = bl::test::stats;

namespace {

constexpr int kResolution = 32, kBlock = 8;

std::uint32_t envOr(const char* name, std::uint32_t fallback) {
    const char* v = std::getenv(name);
    return v ? std::uint32_t(std::strtoul(v, nullptr, 10)) : fallback;
}

// Every triangle of the meshes named `part` on its own three vertices with its face normal,
// turned to the side its vertex normals were on (the file's orientation).
void shadeFlat(Scene& s, const std::string& part) {
    for (Mesh& m : s.meshes) {
        if (m.name.find(part) == std::string::npos) continue;
        Mesh flat = m;
        flat.positions.clear();
        flat.normals.clear();
        flat.uvs.clear();
        flat.triangles.clear();
        for (const glm::uvec3& t : m.triangles) {
            const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
            glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
            if (!m.normals.empty() && glm::dot(n, m.normals[t.x] + m.normals[t.y] + m.normals[t.z]) < 0.0f) n = -n;
            const auto base = std::uint32_t(flat.positions.size());
            for (std::uint32_t i : {t.x, t.y, t.z}) {
                flat.positions.push_back(m.positions[i]);
                flat.normals.push_back(n);
                if (!m.uvs.empty()) flat.uvs.push_back(m.uvs[i]);
            }
            flat.triangles.push_back({base, base + 1, base + 2});
        }
        m = flat;
    }
}

class BidirB3 : public bl::test::VulkanTest {};

} // namespace

TEST_F(BidirB3, DISABLED_VplAgainstBundleSmoothAndFlat) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-glossy-point.toml");
    const std::uint32_t seeds = envOr("B3_SEEDS", 8), frames = envOr("B3_FRAMES", 64), spp = envOr("B3_SPP", 1024);
    for (const bool flat : {false, true}) {
        Scene s = loadScene(bl::test::sourcePath("data/external/cornell-glossy-point.toml"));
        s.camera.resolution = {kResolution, kResolution};
        if (flat) shadeFlat(s, "sphere");
        const std::vector<double> reference =
            stats::blockMeans(bl::test::layerOf(bl::test::renderReference(s, spp), "indirect1"), kBlock);
        std::vector<std::vector<double>> perSeed[2];
        const char* strategies[2] = {"vpl", "bundle"};
        for (int k = 0; k < 2; ++k) {
            for (std::uint32_t seed : stats::seeds(seeds)) {
                std::unique_ptr<Mode> mode = createMode(
                    "bidir", {std::string("strategy=") + strategies[k], "bounces=1", "suppression=none",
                              "vpl_source=traced", "pairs_per_frame=8", "bundle_resolution=128",
                              "shadow_resolution=256", "vpl_shadow_resolution=128"});
                mode->setScene(s, &ctx());
                for (std::uint32_t f = 0; f < frames; ++f) mode->iterate({f, seed, 0.0});
                perSeed[k].push_back(stats::blockMeans(bl::test::layerOf(mode->resolve(), "indirect1"), kBlock));
            }
        }
        std::printf("B3 %s sphere: %u seeds x %u frames, reference %u spp\n", flat ? "flat" : "smooth", seeds, frames,
                    spp);
        std::printf("region  reference   vpl (%%ref +- se)      bundle (%%ref +- se)   vpl-bundle (%% of ref +- se, sigma)\n");
        for (std::size_t r = 0; r < reference.size(); ++r) {
            std::vector<double> v, b;
            for (std::uint32_t i = 0; i < seeds; ++i) v.push_back(perSeed[0][i][r]), b.push_back(perSeed[1][i][r]);
            const stats::Summary sv = stats::summarize(v), sb = stats::summarize(b);
            const stats::Summary d = stats::pairedDifference(v, b);
            const double ref = reference[r];
            std::printf("%2zu  %.5f  %+6.1f +- %4.1f  %+6.1f +- %4.1f  %+6.1f +- %4.1f  (%+.1f)\n", r, ref,
                        100.0 * (sv.mean / ref - 1.0), 100.0 * sv.stderr_ / ref, 100.0 * (sb.mean / ref - 1.0),
                        100.0 * sb.stderr_ / ref, 100.0 * d.mean / ref, 100.0 * d.stderr_ / ref,
                        d.stderr_ > 0.0 ? d.mean / d.stderr_ : 0.0);
        }
    }
}
