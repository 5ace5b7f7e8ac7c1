// bundlelab render SCENE --mode M --out FILE.exr [--width W --height H]
//                  [--spp N | --iterations N | --time SECONDS] [--seed S] [--device D] [--set k=v ...]
#include "base/Error.h"
#include "base/Log.h"
#include "cli/Commands.h"
#include "cli/FiniteRange.h"
#include "cli/OutputFiles.h"
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <memory>

namespace bl::cli {

namespace {

struct RenderOptions {
    std::string scene;
    std::string mode;
    std::string out;
    int width = 0;
    int height = 0;
    std::uint32_t spp = 0;
    std::uint32_t iterations = 0;
    double seconds = 0.0;
    std::uint64_t seed = 0;
    double time = 0.0;
    std::string device;
    bool validation = false;
    std::vector<std::string> assignments;
    std::vector<std::uint32_t> checkpoints;
};

// FILE.exr -> FILE.<iterations>.exr
std::string checkpointPath(const std::string& out, std::uint32_t iterations) {
    std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + "." + std::to_string(iterations) + ".exr")).string();
}

void printTimings(const Mode& mode) {
    PassTimes passes = mode.timings();
    if (passes.empty()) {
        return;
    }
    std::printf("%-20s %10s %8s %12s\n", "pass", "total ms", "count", "ms / pass");
    for (const PassTime& p : passes) {
        std::printf("%-20s %10.3f %8u %12.3f\n", p.name.c_str(), p.totalMs, p.count, p.meanMs());
    }
}

int runRender(const RenderOptions& o) {
    if (std::filesystem::path(o.out).extension() != ".exr") {
        throw Error("--out " + o.out + ": the output must be an .exr file (a .png preview is written beside it)");
    }
    const ModeEntry& entry = findMode(o.mode);
    std::unique_ptr<vk::Context> ctx; // declared before the mode: the mode's GPU objects go first
    std::unique_ptr<Mode> mode = createMode(o.mode, o.assignments); // bad parameters fail before any work
    Scene scene = loadScene(o.scene);
    if (o.width > 0) scene.camera.resolution.x = o.width;
    if (o.height > 0) scene.camera.resolution.y = o.height;

    std::string device;
    if (entry.needsGpu) {
        ctx = std::make_unique<vk::Context>(vk::ContextOptions{o.device, o.validation});
        device = ctx->info().describe();
        std::cout << "device: " << device << "\n";
    }
    mode->setScene(scene, ctx.get());

    // Budget: iterations (--spp is the same for modes whose iteration is one sample per pixel) or
    // wall time; one iteration when nothing is given.
    const std::uint32_t iterations = o.spp ? o.spp : o.iterations ? o.iterations : (o.seconds > 0 ? 0 : 1);
    // Wall time counts iterate() only, as the experiment runner does: writing checkpoints is not
    // the method's cost, and samples/s must not depend on how often one asks for them.
    using Clock = std::chrono::steady_clock;
    RenderRecord record{o.scene, o.mode, device, o.seed, 0.0, false};
    std::uint32_t done = 0;
    try {
        while (iterations ? done < iterations : record.wallSeconds < o.seconds) {
            const auto start = Clock::now();
            mode->iterate({done, o.seed, o.time});
            record.wallSeconds += std::chrono::duration<double>(Clock::now() - start).count();
            ++done;
            if (std::find(o.checkpoints.begin(), o.checkpoints.end(), done) != o.checkpoints.end()) {
                writeRenderOutputs(checkpointPath(o.out, done), mode->resolve(), *mode, record);
                std::cout << "checkpoint " << done << ": " << checkpointPath(o.out, done) << "\n";
            }
        }
    } catch (const std::exception& e) {
        // Keep what was computed: write it as <out>.partial.exr, then report the error.
        record.partial = true;
        if (done > 0) {
            std::string partial = std::filesystem::path(o.out).replace_extension(".partial.exr").string();
            writeRenderOutputs(partial, mode->resolve(), *mode, record);
            std::cerr << "bundlelab: " << done << " iterations saved to " << partial << "\n";
        }
        throw;
    }
    ImageSet images = mode->resolve();
    std::vector<std::string> written = writeRenderOutputs(o.out, images, *mode, record);
    const double samples = double(images.radiance().pixelCount()) * done;
    std::printf("%s: %s, %u iterations, %dx%d, %.3f s, %.4g samples/s\n", o.mode.c_str(), o.scene.c_str(), done,
                images.radiance().width(), images.radiance().height(), record.wallSeconds,
                samples / std::max(record.wallSeconds, 1e-9));
    for (const auto& [name, value] : images.counters) {
        std::printf("%s: %.6g (%.4g per second)\n", name.c_str(), value, value / std::max(record.wallSeconds, 1e-9));
    }
    printTimings(*mode);
    if (images.nonFiniteSamples) {
        log::warn(std::to_string(images.nonFiniteSamples) + " NaN/Inf samples were discarded");
    }
    for (const std::string& f : written) {
        std::cout << "wrote " << f << "\n";
    }
    if (ctx && ctx->validationErrorCount() > 0) {
        std::cerr << "bundlelab: " << ctx->validationErrorCount() << " Vulkan validation errors\n";
        return 3;
    }
    return 0;
}

} // namespace

void addRenderCommand(CLI::App& app, Action& action) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "render a scene with one mode");
    cmd->add_option("scene", o->scene, "scene file (.toml, or a bare .obj/.ply)")->required();
    cmd->add_option("-m,--mode", o->mode, "rendering mode (see `bundlelab modes`)")->required();
    cmd->add_option("-o,--out", o->out, "output EXR; a PNG preview and a JSON record are written beside it")
        ->required();
    cmd->add_option("--width", o->width, "image width (overrides the scene's camera)")
        ->check(CLI::Range(1, kMaxResolution));
    cmd->add_option("--height", o->height, "image height (overrides the scene's camera)")
        ->check(CLI::Range(1, kMaxResolution));
    auto* spp = cmd->add_option("--spp", o->spp, "samples per pixel (iterations of per-pixel-sample modes)")
                    ->check(CLI::Range(1u, 1u << 30));
    auto* its = cmd->add_option("--iterations", o->iterations, "iterations (units of progressive work)")
                    ->check(CLI::Range(1u, 1u << 30));
    auto* secs = cmd->add_option("--time", o->seconds, "render for this many seconds of wall time")
                     ->check(finiteRange(1e-3, 1e7));
    spp->excludes(its)->excludes(secs);
    its->excludes(secs);
    cmd->add_option("--seed", o->seed, "run seed");
    cmd->add_option("--scene-time", o->time, "scene time in seconds (animated scenes)")->check(finiteRange(-1e9, 1e9));
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring (default: a GPU, else lavapipe)");
    cmd->add_flag("--validation", o->validation, "enable Vulkan validation layers; errors fail the run");
    cmd->add_option("--set", o->assignments, "mode parameter key=value (repeatable)");
    cmd->add_option("--checkpoint", o->checkpoints, "also write FILE.<N>.exr after N iterations (repeatable)")
        ->check(CLI::Range(1u, 1u << 30));
    cmd->callback([o, &action] { action = [o] { return runRender(*o); }; });
}

} // namespace bl::cli
