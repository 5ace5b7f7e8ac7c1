#include "runner/TaskRunner.h"

#include "base/Error.h"
#include "base/Json.h"
#include "base/Log.h"
#include "base/RunEnvironment.h"
#include "image/ImageIO.h"
#include "image/Metrics.h"
#include "modes/Registry.h"
#include "modes/SettingTrades.h"
#include "runner/FileUtil.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

namespace fs = std::filesystem;

namespace bl {

namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.9g", v);
    return buf;
}

std::string params(const Task& t) {
    std::string s;
    for (const auto& [k, v] : t.gridPoint) s += (s.empty() ? "" : ";") + k + "=" + formatValue(v);
    return s;
}

} // namespace

TaskRunner::TaskRunner(const ExperimentConfig& config, const ReferenceCache& references, std::string outDir)
    : mConfig(&config), mReferences(&references), mOutDir(std::move(outDir)) {}

std::string TaskRunner::directory(const Task& task) const { return (fs::path(mOutDir) / "tasks" / task.id).string(); }

std::vector<std::string> TaskRunner::tradesOnce(const std::string& key, const std::string& taskId,
                                                const std::function<std::vector<std::string>()>& check) const {
    {
        std::lock_guard lock(mTradesMutex);
        const auto it = mTrades.find(key);
        if (it != mTrades.end()) {
            if (it->second.warnings.empty()) return {};
            return {std::to_string(it->second.warnings.size()) + " setting warning(s) as for task " + it->second.firstTask +
                    " (same scene, resolution, mode and settings)"};
        }
    }
    std::vector<std::string> warnings = check(); // outside the lock: it may take a while
    std::lock_guard lock(mTradesMutex);
    mTrades.emplace(key, SaidTrades{taskId, warnings});
    return warnings;
}

bool TaskRunner::finished(const Task& task) const {
    std::string done;
    return readFileIfExists((fs::path(directory(task)) / "done.json").string(), done) &&
           done.find("\"hash\": \"" + task.hash + "\"") != std::string::npos &&
           fs::is_regular_file(fs::path(directory(task)) / "result.csv");
}

void TaskRunner::run(const Task& task, vk::Context* gpu) const {
    const fs::path dir = directory(task);
    fs::remove_all(dir); // a partial task from a killed run starts over
    fs::create_directories(dir);

    const SceneEntry& entry = mConfig->scene(task.scene);
    Scene scene = loadScene(entry.file);
    if (entry.resolution) scene.camera.resolution = *entry.resolution;
    const ModeEntry& modeEntry = findMode(task.mode);
    Settings settings(modeEntry.parameters());
    for (const auto& [k, v] : task.settings) settings.set(k, v);
    std::unique_ptr<Mode> mode = modeEntry.create(settings);
    if (modeEntry.needsGpu && !gpu) {
        throw Error("task " + task.id + ": mode " + task.mode + " needs a Vulkan device");
    }
    using Clock = std::chrono::steady_clock;
    vk::Context* device = modeEntry.needsGpu ? gpu : nullptr;
    // Set-up (upload, pipelines, precomputation) is timed apart from iterate(): a method's cost is
    // both, and which dominates depends on how many iterations a frame gets.
    auto setUp = [&]() {
        const auto start = Clock::now();
        mode->setScene(scene, device);
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    const double setupSeconds = setUp();
    for (const std::string& w : lightsLeftOut(*mode, scene)) log::warn("task " + task.id + ": " + w);
    {
        std::string key = entry.file + "|" + std::to_string(scene.camera.resolution.x) + "x" +
                          std::to_string(scene.camera.resolution.y) + "|" + task.mode;
        for (const auto& [k, v] : mode->settings().resolved()) key += "|" + k + "=" + v;
        for (const std::string& w : tradesOnce(key, task.id, [&] { return settingTrades(*mode, scene); }))
            log::warn("task " + task.id + ": " + w);
    }

    const RunEnvironment env = currentRunEnvironment();
    const std::string deviceName = modeEntry.needsGpu ? gpu->info().describe() : "";
    {
        std::ostringstream j;
        JsonWriter w(j);
        w.beginObject().field("id", task.id).field("index", task.index).field("scene", task.scene);
        w.field("scene_file", entry.file).field("mode", task.mode).field("label", task.label);
        w.field("seed", static_cast<unsigned long long>(task.seed)).field("hash", task.hash);
        w.field("budget_iterations", task.budget.iterations).field("budget_seconds", task.budget.seconds);
        w.field("frames", task.frames.frames).field("frame_rate", task.frames.frameRate);
        w.key("checkpoints").beginArray();
        for (std::uint32_t c : task.checkpoints) w.value(c);
        w.endArray();
        w.key("settings").beginObject();
        for (const auto& [k, v] : mode->settings().resolved()) w.field(k, v);
        w.endObject().endObject();
        writeFileAtomic((dir / "task.json").string(), j.str() + "\n");
        std::ostringstream e;
        JsonWriter we(e);
        we.beginObject().field("device", deviceName).field("cpu", env.cpu).field("hardware_threads", env.hardwareThreads);
        we.field("build_type", env.buildType).field("git_revision", env.gitRevision).field("version", env.version);
        we.endObject();
        writeFileAtomic((dir / "environment.json").string(), e.str() + "\n");
    }

    const ReferenceImage* reference = mReferences->find(task);
    std::string metrics = "iteration,wall_seconds,gpu_ms,mse,rmse,relmse,smape,mae,mean_ratio_r,mean_ratio_g,"
                          "mean_ratio_b,block_ratio_rms,block_ratio_max\n";
    ImageMetrics last;
    bool haveMetrics = false;
    double wall = 0.0; // time in iterate() only: checkpoints and metrics are not the method's cost
    std::uint32_t done = 0;
    std::uint32_t nextPowerOfTwo = 1;
    auto isCheckpoint = [&](std::uint32_t n) {
        if (task.budget.iterations) {
            return std::find(task.checkpoints.begin(), task.checkpoints.end(), n) != task.checkpoints.end();
        }
        if (n == nextPowerOfTwo) {
            nextPowerOfTwo *= 2;
            return true;
        }
        return false;
    };
    ImageSet images;
    auto checkpoint = [&]() {
        images = mode->resolve();
        writeExr((dir / ("iter-" + std::to_string(done) + ".exr")).string(), images.radiance());
        std::string row = std::to_string(done) + "," + number(wall) + "," + number(gpuMilliseconds(mode->timings()));
        if (reference) {
            Image test = images.radiance(), ref = reference->image;
            matchResolution(test, ref);
            last = computeMetrics(test, ref);
            haveMetrics = true;
            for (double v : {last.mse, last.rmse, last.relMse, last.smape, last.mae, last.meanRatio.x, last.meanRatio.y,
                             last.meanRatio.z, last.blockRatios.rms, last.blockRatios.maxDeviation}) {
                row += "," + number(v);
            }
        } else {
            row += ",,,,,,,,,,";
        }
        metrics += row + "\n";
        writeFileAtomic((dir / "metrics.csv").string(), metrics);
    };
    // One frame's budget of iterations; `afterIteration` sees the count done so far.
    auto runFrame = [&](std::uint32_t frame, const std::function<void()>& afterIteration) {
        while (task.budget.iterations ? done < task.budget.iterations : wall < task.budget.seconds) {
            auto start = Clock::now();
            mode->iterate(task.frames.iteration(frame, done, task.seed));
            wall += std::chrono::duration<double>(Clock::now() - start).count();
            ++done;
            afterIteration();
        }
    };
    runFrame(0, [&]() {
        if (isCheckpoint(done)) {
            checkpoint();
        }
    });
    if (metrics.find("\n" + std::to_string(done) + ",") == std::string::npos) {
        checkpoint(); // a time budget ends between powers of two
    }
    // Frame 0's lost work: a warning in the log, and no result at all from an image that holds
    // none of its work (the task fails with the reason in error.txt).
    const LostWorkVerdict lost = judgeLostWork(task.mode, images);
    for (const std::string& w : lost.warnings) log::warn("task " + task.id + ": " + w);
    if (!lost.refusal.empty()) {
        throw Error(lost.refusal);
    }
    const std::uint32_t frameZeroIterations = done;
    const double frameZeroWall = wall;
    const double frameZeroGpuMs = gpuMilliseconds(mode->timings());
    const PassTimes frameZeroPasses = mode->timings();

    // The other frames of an animated scene: each a new estimate with the same budget, its image
    // and costs recorded (frames.csv); frame 0 stays the one judged against the reference.
    std::string frames = "frame,scene_time,iterations,setup_seconds,wall_seconds,gpu_ms\n";
    auto frameRow = [&](std::uint32_t frame, double setup) {
        frames += std::to_string(frame) + "," + number(task.frames.timeOf(frame)) + "," + std::to_string(done) + "," +
                  number(setup) + "," + number(wall) + "," + number(gpuMilliseconds(mode->timings())) + "\n";
    };
    frameRow(0, setupSeconds);
    if (task.frames.frames > 1) {
        writeExr(framePath((dir / "final.exr").string(), 0), images.radiance());
    }
    for (std::uint32_t frame = 1; frame < task.frames.frames; ++frame) {
        const double setup = setUp();
        done = 0;
        wall = 0.0;
        runFrame(frame, []() {});
        writeExr(framePath((dir / "final.exr").string(), frame), mode->resolve().radiance());
        frameRow(frame, setup);
    }
    writeFileAtomic((dir / "frames.csv").string(), frames);
    done = frameZeroIterations;
    wall = frameZeroWall;

    writeExr((dir / "final.exr").string(), images.radiance());
    writePng((dir / "final.png").string(), images.radiance());
    writePfm((dir / "final.pfm").string(), images.radiance());
    std::string passes = "pass,total_ms,count,mean_ms\n";
    for (const PassTime& p : frameZeroPasses) {
        passes += csvField(p.name) + "," + number(p.totalMs) + "," + std::to_string(p.count) + "," + number(p.meanMs()) + "\n";
    }
    writeFileAtomic((dir / "passes.csv").string(), passes);

    std::string row = std::to_string(task.index) + "," + csvField(task.id) + "," + csvField(task.scene) + "," +
                      csvField(task.mode) + "," + csvField(task.label) + "," + csvField(params(task)) + "," +
                      std::to_string(task.seed) + "," + std::to_string(done) + "," + number(wall) + "," +
                      number(setupSeconds) + "," + number(frameZeroGpuMs);
    if (haveMetrics) {
        for (double v : {last.mse, last.rmse, last.relMse, last.smape, last.mae, last.meanRatio.x, last.meanRatio.y,
                         last.meanRatio.z, last.blockRatios.rms}) {
            row += "," + number(v);
        }
        row += "," + number(reference->noiseRelMse);
    } else {
        row += ",,,,,,,,,,";
    }
    row += "," + csvField(fs::relative(dir, mOutDir).string());
    if (reference) {
        // Which reference image this task is judged against (the report shows it beside).
        writeFileAtomic((dir / "reference.txt").string(), fs::relative(reference->path, dir).string() + "\n");
    }
    writeFileAtomic((dir / "result.csv").string(), row + "\n");
    writeFileAtomic((dir / "done.json").string(), "{\n  \"hash\": \"" + task.hash + "\",\n  \"iterations\": " +
                                                      std::to_string(done) + ",\n  \"wall_seconds\": " + number(wall) +
                                                      ",\n  \"setup_seconds\": " + number(setupSeconds) + "\n}\n");
}

} // namespace bl
