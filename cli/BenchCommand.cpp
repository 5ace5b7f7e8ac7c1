// bundlelab bench bundles SCENE [--resolution N ...] [--directions K] [--synthetic T] [--json FILE]
//
// A benchmark, not a test: per bundle, GPU milliseconds of the build (every fragment into the
// lists), of a traversal that walks every list once, and of the floor (the same rasterization
// with a fragment shader that only counts); fragments and list lengths. Medians over the
// directions after one warm-up direction (shaders compile on first draw).
#include "base/Error.h"
#include "base/Json.h"
#include "base/RunEnvironment.h"
#include "bundle/BundleBuilder.h"
#include "bundle/BundleFrame.h"
#include "bundle/DirectionSampler.h"
#include "cli/Commands.h"
#include "cli/Median.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <cmath>

namespace bl::cli {

namespace {

struct BenchOptions {
    std::string scene;
    std::vector<std::uint32_t> resolutions{256, 512, 1024, 2048};
    std::uint32_t directions = 8;
    std::uint64_t synthetic = 0;
    std::string json;
    std::string device;
    std::string backend = "auto"; // the modes' rule: chooseBundleBackend
};

// A height field of `triangles` triangles over [-1, 1]^2: a stand-in for a dense scan.
Scene syntheticScene(std::uint64_t triangles) {
    const auto side = static_cast<std::uint32_t>(std::max(2.0, std::ceil(std::sqrt(triangles / 2.0))));
    Scene s;
    s.materials.push_back(Material{});
    Mesh m;
    m.name = "synthetic";
    for (std::uint32_t j = 0; j <= side; ++j) {
        for (std::uint32_t i = 0; i <= side; ++i) {
            float x = -1.0f + 2.0f * i / side, z = -1.0f + 2.0f * j / side;
            float y = 0.1f * std::sin(9.0f * x) * std::cos(7.0f * z);
            m.positions.emplace_back(x, y, z);
            m.normals.emplace_back(0.0f, 1.0f, 0.0f);
        }
    }
    for (std::uint32_t j = 0; j < side; ++j) {
        for (std::uint32_t i = 0; i < side; ++i) {
            std::uint32_t a = j * (side + 1) + i, b = a + 1, c = a + side + 1, d = c + 1;
            m.triangles.emplace_back(a, c, d);
            m.triangles.emplace_back(a, d, b);
        }
    }
    s.meshes.push_back(std::move(m));
    return s;
}

int runBench(const BenchOptions& o) {
    if (o.scene.empty() == (o.synthetic == 0)) {
        throw Error("bench bundles: give a SCENE or --synthetic TRIANGLES (one of them)");
    }
    Scene scene = o.synthetic ? syntheticScene(o.synthetic) : loadScene(o.scene);
    const std::string name = o.synthetic ? "synthetic-" + std::to_string(scene.triangleCount()) : o.scene;
    vk::Context ctx(vk::ContextOptions{o.device, false});
    gpu::GpuScene gpuScene(ctx, scene);
    BundleBuilderOptions options;
    options.listStatistics = true;
    options.backend = chooseBundleBackend(ctx, o.backend);
    const std::string backendName = options.backend == BundleBackend::Compute ? "compute" : "raster";
    BundleBuilder builder(ctx, gpuScene, options);
    DirectionSampler sampler(DirectionSequence::Halton, 0);
    const Bounds b = scene.bounds();
    std::printf("device: %s\nscene: %s, %zu triangles, build backend %s, subgroup allocation %s, exact depths %s\n",
                ctx.info().describe().c_str(), name.c_str(), scene.triangleCount(), backendName.c_str(),
                builder.usesSubgroups() ? "yes" : "no", builder.exactDepths() ? "yes" : "no");
    std::printf("%10s %12s %10s %10s %10s %12s %8s %8s %10s\n", "resolution", "fragments", "floor ms", "build ms",
                "walk ms", "(b+w)/floor", "mean len", "max len", "rebuilds");
    std::ostringstream json;
    JsonWriter w(json);
    w.beginObject().field("scene", name).field("triangles", static_cast<unsigned long long>(scene.triangleCount()));
    w.field("device", ctx.info().describe()).field("git_revision", currentRunEnvironment().gitRevision);
    w.field("directions", o.directions).field("backend", backendName).field("subgroup_allocation", builder.usesSubgroups());
    w.key("results").beginArray();
    for (std::uint32_t res : o.resolutions) {
        std::vector<double> floorMs, buildMs, walkMs, fragments, meanLength;
        std::uint32_t longest = 0, rebuilds = 0;
        for (std::uint32_t k = 0; k <= o.directions; ++k) {
            BundleDirection d = sampler.sample(k);
            shader::BundleFrame frame = bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), res);
            double floor = 0.0;
            builder.countFragments(frame, 0.0, &floor);
            BundleStats stats = builder.build(frame, 0.0, [](const BuiltBundle&) {});
            if (k == 0) continue; // warm-up: first draws compile shaders
            floorMs.push_back(floor);
            buildMs.push_back(stats.buildMs);
            walkMs.push_back(stats.traverseMs);
            fragments.push_back(double(stats.fragments));
            meanLength.push_back(stats.meanListLength());
            longest = std::max(longest, stats.longestList);
            rebuilds += stats.rebuilds;
        }
        const double f = median(floorMs), bms = median(buildMs), wms = median(walkMs);
        std::printf("%10u %12.0f %10.3f %10.3f %10.3f %12.2f %8.2f %8u %10u\n", res, median(fragments), f, bms, wms,
                    f > 0 ? (bms + wms) / f : 0.0, median(meanLength), longest, rebuilds);
        w.beginObject().field("resolution", res).field("fragments_median", median(fragments));
        w.field("floor_ms_median", f).field("build_ms_median", bms).field("traverse_ms_median", wms);
        w.field("ratio_to_floor", f > 0 ? (bms + wms) / f : 0.0).field("mean_list_length", median(meanLength));
        w.field("longest_list", longest).field("rebuilds", rebuilds).endObject();
    }
    w.endArray().endObject();
    if (!o.json.empty()) {
        std::ofstream(o.json) << json.str() << "\n";
        std::printf("wrote %s\n", o.json.c_str());
    }
    return 0;
}

} // namespace

void addBenchCommand(CLI::App& app, Action& action) {
    CLI::App* bench = app.add_subcommand("bench", "benchmarks (timings, not pass/fail)");
    bench->require_subcommand(1);
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = bench->add_subcommand("bundles", "bundle build and traversal ms against the rasterization floor");
    cmd->add_option("scene", o->scene, "scene file (or --synthetic)");
    cmd->add_option("--resolution", o->resolutions, "bundle resolutions (repeatable)")->check(CLI::Range(16u, 8192u));
    cmd->add_option("--directions", o->directions, "directions measured (after one warm-up)")->check(CLI::Range(1u, 100000u));
    cmd->add_option("--synthetic", o->synthetic, "a generated height field of this many triangles instead of a scene")
        ->check(CLI::Range(2ull, 100000000ull));
    cmd->add_option("--json", o->json, "also write the results as JSON");
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring");
    cmd->add_option("--backend", o->backend,
                    "bundle build: auto (the modes' choice: compute on a CPU device, raster on GPUs), raster (graphics "
                    "pipeline) or compute (floor: raster)")
        ->check(CLI::IsMember({"auto", "raster", "compute"}));
    cmd->callback([o, &action] { action = [o] { return runBench(*o); }; });
    addBenchTexelsCommand(*bench, action);
}

} // namespace bl::cli
