// bundlelab render SCENE --mode M --out FILE.exr [--width W --height H]
//                  [--spp N | --iterations N | --time SECONDS] [--seed S] [--device D] [--set k=v ...]
//                  [--scene-time T] [--frames N [--fps R]]
// With --frames N > 1 the scene is rendered at times T + f / R, f = 0 .. N-1, each frame its own
// estimate with the whole budget, written as FILE.frame0000.exr (.png, .json) and so on.
#include "base/Error.h"
#include "base/Log.h"
#include "cli/Commands.h"
#include "cli/FiniteRange.h"
#include "cli/OutputFiles.h"
#include "modes/FrameSchedule.h"
#include "modes/Registry.h"
#include "modes/SettingTrades.h"
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
    double time = 0.0; // scene time of the (first) frame
    std::uint32_t frames = 1;
    double frameRate = kDefaultFrameRate;
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

// Renders one frame (setScene, then the budget of iterations) into `out`; prints its summary.
void renderFrame(const RenderOptions& o, const FrameSchedule& schedule, std::uint32_t frame, const std::string& out,
                 const Scene& scene, Mode& mode, vk::Context* ctx, RenderRecord& record) {
    using Clock = std::chrono::steady_clock;
    record.frame = frame;
    record.sceneTime = schedule.timeOf(frame);
    record.wallSeconds = 0.0;
    const auto setupStart = Clock::now();
    mode.setScene(scene, ctx); // a new estimate for every frame
    record.setupSeconds = std::chrono::duration<double>(Clock::now() - setupStart).count();

    // Budget: iterations (--spp is the same for modes whose iteration is one sample per pixel) or
    // wall time; one iteration when nothing is given.
    const std::uint32_t iterations = o.spp ? o.spp : o.iterations ? o.iterations : (o.seconds > 0 ? 0 : 1);
    // Wall time counts iterate() only, as the experiment runner does: writing checkpoints is not
    // the method's cost, and samples/s must not depend on how often one asks for them.
    std::uint32_t done = 0;
    try {
        while (iterations ? done < iterations : record.wallSeconds < o.seconds) {
            const auto start = Clock::now();
            mode.iterate(schedule.iteration(frame, done, o.seed));
            record.wallSeconds += std::chrono::duration<double>(Clock::now() - start).count();
            ++done;
            if (std::find(o.checkpoints.begin(), o.checkpoints.end(), done) != o.checkpoints.end()) {
                writeRenderOutputs(checkpointPath(out, done), mode.resolve(), mode, record);
                std::cout << "checkpoint " << done << ": " << checkpointPath(out, done) << "\n";
            }
        }
    } catch (const std::exception& e) {
        // Keep what was computed: write it as <out>.partial.exr, then report the error.
        record.partial = true;
        if (done > 0) {
            std::string partial = std::filesystem::path(out).replace_extension(".partial.exr").string();
            writeRenderOutputs(partial, mode.resolve(), mode, record);
            std::cerr << "bundlelab: " << done << " iterations saved to " << partial << "\n";
        }
        throw;
    }
    ImageSet images = mode.resolve();
    // Lost work is reported at the end of every render; an image built on none of its work is
    // refused before it is written (checkpoints and earlier frames already written stay).
    const LostWorkVerdict lost = judgeLostWork(o.mode, images);
    for (const std::string& w : lost.warnings) log::warn(w);
    if (!lost.refusal.empty()) {
        throw Error(lost.refusal + " (" + out + ")");
    }
    std::vector<std::string> written = writeRenderOutputs(out, images, mode, record);
    const double samples = double(images.radiance().pixelCount()) * done;
    if (schedule.frames > 1) {
        std::printf("frame %u of %u, scene time %.6g s\n", frame, schedule.frames, record.sceneTime);
    }
    std::printf("%s: %s, %u iterations, %dx%d, %.3f s, %.4g samples/s; set-up %.3f s\n", o.mode.c_str(),
                o.scene.c_str(), done, images.radiance().width(), images.radiance().height(), record.wallSeconds,
                samples / std::max(record.wallSeconds, 1e-9), record.setupSeconds);
    for (const auto& [name, value] : images.counters) {
        std::printf("%s: %.6g (%.4g per second)\n", name.c_str(), value, value / std::max(record.wallSeconds, 1e-9));
    }
    printTimings(mode);
    for (const std::string& f : written) {
        std::cout << "wrote " << f << "\n";
    }
}

int runRender(const RenderOptions& o) {
    if (std::filesystem::path(o.out).extension() != ".exr") {
        throw Error("--out " + o.out + ": the output must be an .exr file (a .png preview is written beside it)");
    }
    const FrameSchedule schedule{o.frames, o.frameRate, o.time};
    schedule.validate("--frames/--fps/--scene-time");
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
    // Once per render, before any work: what of the scene's light this mode leaves out, and what
    // its settings trade on this scene (modes/SettingTrades.h).
    for (const std::string& w : lightsLeftOut(*mode, scene)) log::warn(w);
    for (const std::string& w : settingTrades(*mode, scene)) log::warn(w);
    RenderRecord record{o.scene, o.mode, device, o.seed};
    for (std::uint32_t frame = 0; frame < schedule.frames; ++frame) {
        const std::string out = schedule.frames > 1 ? framePath(o.out, frame) : o.out;
        renderFrame(o, schedule, frame, out, scene, *mode, ctx.get(), record);
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
    cmd->add_option("scene", o->scene, "scene file (.toml, Mitsuba 3 .xml, or a bare .obj/.ply)")->required();
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
    cmd->add_option("--scene-time", o->time, "scene time in seconds (animated scenes; of frame 0 with --frames)")
        ->check(finiteRange(-1e9, 1e9));
    cmd->add_option("--frames", o->frames, "render N frames, each with the whole budget, as FILE.frame0000.exr ...")
        ->check(CLI::Range(1u, 1u << 20));
    cmd->add_option("--fps", o->frameRate, "frames per second of scene time, with --frames (default 24)")
        ->check(finiteRange(1e-6, 1e6));
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring (default: a GPU, else lavapipe)");
    cmd->add_flag("--validation", o->validation, "enable Vulkan validation layers; errors fail the run");
    cmd->add_option("--set", o->assignments, "mode parameter key=value (repeatable)");
    cmd->add_option("--checkpoint", o->checkpoints, "also write FILE.<N>.exr after N iterations (repeatable)")
        ->check(CLI::Range(1u, 1u << 30));
    cmd->callback([o, &action] { action = [o] { return runRender(*o); }; });
}

} // namespace bl::cli
