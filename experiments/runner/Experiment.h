// bundlelab run: an experiment config -> its task list -> a results directory. Finished tasks are
// skipped, so running the same config again finishes at once, and a task killed mid-way is redone
// with nothing else lost. Tasks run on a local pool (GPU tasks one at a time per device) or as a
// slice (--task-index/--task-count) for a cluster job array.
#pragma once

#include <string>

namespace bl {

struct RunOptions {
    std::string outDir;
    int jobs = 1;
    int taskIndex = -1; // with taskCount: run tasks whose index % taskCount == taskIndex
    int taskCount = 1;
    std::string device;
    bool validation = false;
};

// Returns the number of tasks that failed (their errors are logged and kept in error.txt).
int runExperiment(const std::string& configPath, const RunOptions& options);

} // namespace bl
