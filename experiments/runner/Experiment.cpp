#include "runner/Experiment.h"

#include "base/Error.h"
#include "base/Json.h"
#include "base/Log.h"
#include "base/RunEnvironment.h"
#include "runner/ExperimentConfig.h"
#include "runner/FileUtil.h"
#include "runner/Progress.h"
#include "runner/ReferenceCache.h"
#include "runner/TaskRunner.h"
#include "vk/Context.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace bl {

namespace {

void writeResultsIndex(const ExperimentConfig& config, const TaskRunner& runner, const std::string& outDir) {
    std::string csv = std::string(kResultsHeader) + "\n";
    for (const Task& t : config.tasks) {
        std::string row;
        if (runner.finished(t) && readFileIfExists((fs::path(runner.directory(t)) / "result.csv").string(), row)) {
            csv += row;
        }
    }
    writeFileAtomic((fs::path(outDir) / "results.csv").string(), csv);
}

} // namespace

void writeRunEnvironment(const ExperimentConfig& config, const std::string& configPath, const std::string& device,
                         int jobs, const std::string& outDir) {
    const RunEnvironment env = currentRunEnvironment();
    std::ostringstream e;
    JsonWriter w(e);
    w.beginObject().field("experiment", config.name).field("config", configPath).field("device", device);
    w.field("cpu", env.cpu).field("hardware_threads", env.hardwareThreads).field("build_type", env.buildType);
    w.field("git_revision", env.gitRevision).field("version", env.version).field("jobs", jobs).endObject();
    writeFileAtomic((fs::path(outDir) / "environment.json").string(), e.str() + "\n");
}

std::string devicesOfTasks(const ExperimentConfig& config, const std::string& outDir) {
    std::set<std::string> devices;
    for (const Task& t : config.tasks) {
        std::string text;
        if (!fs::is_regular_file(fs::path(outDir) / "tasks" / t.id / "done.json")) continue; // finished tasks only
        if (!readFileIfExists((fs::path(outDir) / "tasks" / t.id / "environment.json").string(), text)) continue;
        const std::string key = "\"device\": \"";
        const auto start = text.find(key);
        if (start == std::string::npos) continue;
        const auto end = text.find('"', start + key.size());
        if (end != std::string::npos && end > start + key.size()) devices.insert(text.substr(start + key.size(), end - start - key.size()));
    }
    std::string all;
    for (const std::string& d : devices) all += (all.empty() ? "" : "; ") + d;
    return all;
}

std::string resultsDirectory(const ExperimentConfig& config, const RunOptions& options) {
    return options.outDir.empty() ? (fs::path("results") / config.name).string() : options.outDir;
}

std::vector<UnfinishedTask> collectResults(const ExperimentConfig& config, const std::string& outDir) {
    ReferenceCache noReferences(config, outDir);
    TaskRunner runner(config, noReferences, outDir);
    writeResultsIndex(config, runner, outDir);
    std::vector<UnfinishedTask> unfinished;
    for (const Task& t : config.tasks) {
        if (runner.finished(t)) continue;
        UnfinishedTask u{t.index, t.id, ""};
        if (readFileIfExists((fs::path(runner.directory(t)) / "error.txt").string(), u.error)) {
            u.error = u.error.substr(0, u.error.find('\n'));
        }
        unfinished.push_back(u);
    }
    return unfinished;
}

int runExperiment(const std::string& configPath, const RunOptions& options) {
    ExperimentConfig config = loadExperimentConfig(configPath);
    const std::string outDir = resultsDirectory(config, options);
    fs::create_directories(outDir);
    std::string text;
    readFileIfExists(configPath, text);
    writeFileAtomic((fs::path(outDir) / "experiment.toml").string(), text);

    std::vector<const Task*> mine;
    for (const Task& t : config.tasks) {
        if (options.taskIndex < 0 || int(t.index % std::uint32_t(options.taskCount)) == options.taskIndex) {
            mine.push_back(&t);
        }
    }
    ReferenceCache references(config, outDir);
    TaskRunner runner(config, references, outDir);
    std::vector<const Task*> pending;
    for (const Task* t : mine) {
        if (!runner.finished(*t)) pending.push_back(t);
    }
    log::info(config.name + ": " + std::to_string(config.tasks.size()) + " tasks, " + std::to_string(mine.size()) +
              " in this slice, " + std::to_string(mine.size() - pending.size()) + " already finished");
    if (options.referencesOnly) {
        // A cluster's reference job: every reference of the slice, once, before the array starts.
        std::vector<const Task*> all(mine.begin(), mine.end());
        references.prepare(all);
        return 0;
    }
    if (!pending.empty()) {
        references.prepare(pending);
    }

    std::unique_ptr<vk::Context> gpu;
    std::string device;
    for (const Task* t : pending) {
        if (t->needsGpu && !gpu) {
            gpu = std::make_unique<vk::Context>(vk::ContextOptions{options.device, options.validation});
            device = gpu->info().describe();
            log::info("device: " + device);
        }
    }
    writeRunEnvironment(config, configPath, device, options.jobs, outDir);

    Progress progress(pending.size());
    std::mutex gpuMutex, queueMutex;
    std::size_t next = 0;
    std::atomic<int> failures{0};
    auto worker = [&]() {
        for (;;) {
            const Task* task = nullptr;
            {
                std::lock_guard lock(queueMutex);
                if (next >= pending.size()) return;
                task = pending[next++];
            }
            auto start = std::chrono::steady_clock::now();
            try {
                if (task->needsGpu) {
                    std::lock_guard gpuLock(gpuMutex); // one GPU task at a time per device
                    runner.run(*task, gpu.get());
                } else {
                    runner.run(*task, nullptr);
                }
            } catch (const std::exception& e) {
                ++failures;
                log::error("task " + task->id + " failed: " + e.what());
                writeFileAtomic((fs::path(runner.directory(*task)) / "error.txt").string(), std::string(e.what()) + "\n");
            }
            double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::lock_guard lock(queueMutex);
            progress.taskDone(task->id, seconds);
            writeResultsIndex(config, runner, outDir); // a crash later never loses this task
        }
    };
    const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(pending.size())));
    std::vector<std::thread> threads;
    for (int i = 1; i < jobs; ++i) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
    progress.finish();
    writeResultsIndex(config, runner, outDir);
    std::printf("results: %s (results.csv, tasks/)\n", outDir.c_str());
    return failures;
}

} // namespace bl
