// bundlelab run: an experiment config -> its task list -> a results directory. Finished tasks are
// skipped, so running the same config again finishes at once, and a task killed mid-way is redone
// with nothing else lost. Tasks run on a local pool (GPU tasks one at a time per device) or as a
// slice (--task-index/--task-count) for a cluster job array (runner/SlurmArray.h submits one).
#pragma once

#include "runner/ExperimentConfig.h"

#include <string>
#include <vector>

namespace bl {

struct RunOptions {
    std::string outDir;
    int jobs = 1;
    int taskIndex = -1; // with taskCount: run tasks whose index % taskCount == taskIndex
    int taskCount = 1;
    std::string device;
    bool validation = false;
    bool referencesOnly = false; // render (or find cached) the references, run no task
};

// The results directory: --out, else results/<experiment name>.
std::string resultsDirectory(const ExperimentConfig& config, const RunOptions& options);

// Returns the number of tasks that failed (their errors are logged and kept in error.txt).
int runExperiment(const std::string& configPath, const RunOptions& options);

// A task of the config without a finished result in the results directory, and why when it is
// known (the first line of its error.txt; empty when it was killed, timed out or never ran).
struct UnfinishedTask {
    std::uint32_t index = 0;
    std::string id;
    std::string error;
};

// DIR/environment.json: the machine and build a run's report names, and its GPU device ("" for none).
void writeRunEnvironment(const ExperimentConfig& config, const std::string& configPath, const std::string& device,
                         int jobs, const std::string& outDir);
// The devices the finished tasks of DIR ran on (their environment.json), distinct, "; "-separated:
// a run split into slices or array elements names them all, as a local run names its one.
std::string devicesOfTasks(const ExperimentConfig& config, const std::string& outDir);

// Rewrites DIR/results.csv from every finished task (in task order, whoever ran them: a local
// pool, slices, array tasks) and returns the tasks still unfinished.
std::vector<UnfinishedTask> collectResults(const ExperimentConfig& config, const std::string& outDir);

} // namespace bl
