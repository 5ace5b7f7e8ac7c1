// Benchmark (not a test: disabled unless asked for) of mode multibounce, perfect vs imperfect
// bundles: milliseconds per iteration split by pass, from the mode's GPU timer after every
// iteration, medians over the timed iterations after warm-up ones (lavapipe compiles some shader
// variants on first use; the pool grows in the first iteration; static scenes render their shadow
// cubes once). Both bundle kinds run in the same process, one after the other, per scene.
//
//   BL_BENCH_SCENES=a.toml,b.toml BL_BENCH_WARMUP=2 BL_BENCH_ITERATIONS=5
//   BL_BENCH_SETTINGS="bundle_count=16,points=16384"   (environment, all optional)
//   test_multibounce --gtest_also_run_disabled_tests --gtest_filter='MultibounceBench.*'
//
// Groups: build = surface points + bundle build + bundle sort; paths = the path pass (stepping and
// shading every vertex, one pass); camera = G-buffer. Wall = iterate() on the host.
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

using namespace bl;

namespace {

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string item; std::getline(s, item, ',');) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::string env(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v ? std::string(v) : fallback;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

const std::map<std::string, std::string> kGroupOf{{"surface points", "build"}, {"bundle build", "build"},
                                                  {"bundle sort", "build"},    {"paths", "paths"},
                                                  {"gbuffer", "camera"}};

double total(const PassTimes& times, const std::string& group) {
    double ms = 0.0;
    for (const PassTime& t : times) {
        auto it = kGroupOf.find(t.name);
        if (it != kGroupOf.end() && it->second == group) ms += t.totalMs;
    }
    return ms;
}

class MultibounceBench : public bl::test::VulkanTest {};

} // namespace

TEST_F(MultibounceBench, DISABLED_PassTimesPerfectVsImperfect) {
    const std::vector<std::string> scenes =
        split(env("BL_BENCH_SCENES", "data/cornell-box/cornell-point.toml,data/external/sponza-point.toml,"
                                     "data/external/bunny-envmap.toml,experiments/multibounce/bunnies-1m.toml"));
    const int warmup = std::atoi(env("BL_BENCH_WARMUP", "2").c_str());
    const int timed = std::atoi(env("BL_BENCH_ITERATIONS", "5").c_str());
    const std::vector<std::string> extra = split(env("BL_BENCH_SETTINGS", ""));
    const int resolution = std::atoi(env("BL_BENCH_RESOLUTION", "256").c_str());
    std::printf("| scene | triangles | bundles | build | paths | camera | frame | wall | nodes | build imp/perf | "
                "frame imp/perf |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& file : scenes) {
        if (const std::string missing = file[0] == '/' ? "" : bl::test::missingSharedFileOf(file); !missing.empty()) {
            std::printf("%s left out: needs %s (../shared is not here)\n", file.c_str(), missing.c_str());
            continue;
        }
        Scene scene = loadScene(file[0] == '/' ? file : bl::test::sourcePath(file));
        scene.camera.resolution = {resolution, resolution};
        std::map<std::string, double> perfectMedian;
        for (const std::string bundles : {"perfect", "imperfect"}) {
            std::vector<std::string> settings = extra;
            settings.push_back("bundles=" + bundles);
            std::unique_ptr<Mode> mode = createMode("multibounce", settings);
            mode->setScene(scene, &ctx());
            std::map<std::string, std::vector<double>> samples;
            PassTimes before;
            for (int i = 0; i < warmup + timed; ++i) {
                const auto start = std::chrono::steady_clock::now();
                mode->iterate({static_cast<std::uint32_t>(i), 1, 0.0});
                const double wall =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                const PassTimes after = mode->timings();
                if (i >= warmup) {
                    double frame = 0.0;
                    for (const char* g : {"build", "paths", "camera"}) {
                        const double ms = total(after, g) - total(before, g);
                        samples[g].push_back(ms);
                        frame += ms;
                    }
                    samples["frame"].push_back(frame);
                    samples["wall"].push_back(wall);
                }
                before = after;
            }
            const ImageSet out = mode->resolve();
            double nodes = 0.0;
            for (const auto& [name, value] : out.counters) {
                if (name == "bundle_nodes_last") nodes = value;
            }
            std::map<std::string, double> m;
            for (const auto& [g, v] : samples) m[g] = median(v);
            std::string ratios = " | |";
            if (bundles == "perfect") {
                perfectMedian = m;
            } else {
                char text[64];
                std::snprintf(text, sizeof text, " %.3f | %.3f |", m["build"] / perfectMedian["build"],
                              m["frame"] / perfectMedian["frame"]);
                ratios = text;
            }
            std::printf("| %s | %zu | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f |%s\n",
                        file.substr(file.find_last_of('/') + 1).c_str(), scene.triangleCount(), bundles.c_str(),
                        m["build"], m["paths"], m["camera"], m["frame"], m["wall"], nodes, ratios.c_str());
            std::fflush(stdout);
        }
    }
}
