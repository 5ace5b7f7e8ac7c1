// `bundlelab run CONFIG --slurm`: the experiment's unfinished tasks as one Slurm job array, one
// array element per task, each element an ordinary `bundlelab run --task-index I --task-count N`
// so that a cluster run resumes exactly like a local one. References that are not cached yet are
// rendered first by one job the array depends on, never by several elements at once.
//
// Everything lands under DIR/slurm/: submit-K.sbatch (the K-th submission's array script),
// references-K.sbatch, logs/JOB_ELEMENT.out, and submissions.tsv (job, element, task index, task id)
// which maps a log to its task. The jobs carry one name per results directory, so the scheduler's
// queue tells whether any of them is still pending or running; while one is, nothing is submitted
// (a task is never run twice at once). Running the same command again submits only the tasks
// still unfinished: killed, timed out, failed or never run.
#pragma once

#include "runner/Experiment.h"
#include "runner/ExperimentConfig.h"

#include <string>
#include <vector>

namespace bl {

struct SlurmOptions {
    std::string partition;               // #SBATCH --partition (empty: the cluster's default)
    std::string time;                    // #SBATCH --time per element (empty: the partition's default)
    int maxParallel = 0;                 // the array's %N throttle (0: none)
    std::vector<std::string> sbatchArgs; // more #SBATCH options, verbatim ("--gres=gpu:1")
};

// Submits the array (and the reference job it needs); returns the process exit status.
int submitSlurmArray(const std::string& configPath, const RunOptions& run, const SlurmOptions& slurm);

// `bundlelab run CONFIG --collect`: merges every finished task into results.csv, lists the
// unfinished ones with their error or log, and says whether jobs of this directory are still in
// the queue. Returns 0 when every task is finished, 1 otherwise.
int collectSlurmArray(const std::string& configPath, const RunOptions& run);

} // namespace bl
