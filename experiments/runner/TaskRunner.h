// Runs one task of an experiment into DIR/tasks/<id>/: task.json (resolved config), checkpoint
// EXRs, metrics.csv (iteration, wall s, GPU ms, every metric against the reference), passes.csv,
// environment.json, final.{exr,png,pfm}, frames.csv (per frame: scene time, set-up and iteration
// seconds) and final.frameNNNN.exr with several frames, result.csv (its row of results.csv, with
// frame 0's set-up seconds beside its iteration seconds), and done.json last:
// a task without done.json (killed mid-way) is redone from scratch on the next run.
#pragma once

#include "runner/ExperimentConfig.h"
#include "runner/ReferenceCache.h"

#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace bl {

namespace vk {
class Context;
}

inline constexpr const char* kResultsHeader =
    "index,id,scene,mode,label,params,seed,iterations,wall_seconds,setup_seconds,gpu_ms,mse,rmse,relmse,smape,mae,"
    "mean_ratio_r,mean_ratio_g,mean_ratio_b,block_ratio_rms,reference_noise_relmse,dir";

class TaskRunner {
public:
    TaskRunner(const ExperimentConfig& config, const ReferenceCache& references, std::string outDir);

    std::string directory(const Task& task) const;
    // True when the task finished with this exact configuration (its hash).
    bool finished(const Task& task) const;
    // Runs the task; `gpu` must be non-null for GPU modes. Throws on failure (the task stays
    // unfinished).
    void run(const Task& task, vk::Context* gpu) const;

private:
    // What a mode's settings trade on a scene (modes/SettingTrades.h) depends on the scene, its
    // resolution, the mode and its settings, not on the seed: checked once per such key and said
    // once, the tasks that share it pointing to the first (the cut-path check renders the reference).
    struct SaidTrades {
        std::string firstTask;
        std::vector<std::string> warnings;
    };
    std::vector<std::string> tradesOnce(const std::string& key, const std::string& taskId,
                                        const std::function<std::vector<std::string>()>& check) const;

    const ExperimentConfig* mConfig;
    const ReferenceCache* mReferences;
    std::string mOutDir;
    mutable std::mutex mTradesMutex;
    mutable std::map<std::string, SaidTrades> mTrades;
};

} // namespace bl
