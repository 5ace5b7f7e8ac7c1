// bundlelab run CONFIG.toml [--out DIR] [--jobs N] [--task-index I --task-count N]
// bundlelab run CONFIG.toml [--out DIR] --slurm [--partition P] [--time T] [--max-parallel N] [--sbatch ARG]...
// bundlelab run CONFIG.toml [--out DIR] --collect
// bundlelab report RESULTS_DIR
#include "base/Error.h"
#include "cli/Commands.h"
#include "runner/Experiment.h"
#include "runner/SlurmArray.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

namespace bl::cli {

void addRunCommand(CLI::App& app, Action& action) {
    auto o = std::make_shared<RunOptions>();
    auto config = std::make_shared<std::string>();
    auto slurm = std::make_shared<SlurmOptions>();
    auto useSlurm = std::make_shared<bool>(false);
    auto collect = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("run", "run an experiment config: its task grid into a results directory");
    cmd->add_option("config", *config, "experiment config (TOML; see experiments/README.md)")->required();
    cmd->add_option("-o,--out", o->outDir, "results directory (default: results/<experiment name>)");
    cmd->add_option("-j,--jobs", o->jobs, "tasks at once (GPU tasks still run one at a time)")->check(CLI::Range(1, 256));
    auto* index = cmd->add_option("--task-index", o->taskIndex, "run only tasks with index % task-count == task-index")
                      ->check(CLI::Range(0, 1 << 30));
    auto* count = cmd->add_option("--task-count", o->taskCount, "number of slices (a job array's size)")
                      ->check(CLI::Range(1, 1 << 30));
    index->needs(count);
    count->needs(index);
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring");
    cmd->add_flag("--validation", o->validation, "Vulkan validation layers on");
    cmd->add_flag("--references-only", o->referencesOnly,
                  "render (or find cached) the references of the tasks, run none (a cluster's reference job)");
    auto* slurmFlag = cmd->add_flag("--slurm", *useSlurm,
                                    "submit the unfinished tasks as a Slurm job array (sbatch) instead of running them");
    auto* collectFlag = cmd->add_flag("--collect", *collect,
                                      "merge finished tasks into results.csv and list the unfinished ones; run nothing");
    auto* partition = cmd->add_option("--partition", slurm->partition, "with --slurm: the partition");
    auto* time = cmd->add_option("--time", slurm->time, "with --slurm: time limit per array element (sbatch --time)");
    auto* maxParallel = cmd->add_option("--max-parallel", slurm->maxParallel, "with --slurm: array elements at once")
                            ->check(CLI::Range(1, 1 << 20));
    auto* sbatch = cmd->add_option("--sbatch", slurm->sbatchArgs,
                                   "with --slurm: one more sbatch option, verbatim (repeatable; e.g. --sbatch=--gres=gpu:1)")
                       ->allow_extra_args(false);
    for (CLI::Option* opt : {partition, time, maxParallel, sbatch}) opt->needs(slurmFlag);
    slurmFlag->excludes(collectFlag)->excludes(index)->excludes(cmd->get_option("--jobs"));
    collectFlag->excludes(index)->excludes(cmd->get_option("--jobs"));
    cmd->callback([o, config, slurm, useSlurm, collect, &action] {
        action = [o, config, slurm, useSlurm, collect] {
            if (*useSlurm) return submitSlurmArray(*config, *o, *slurm);
            if (*collect) return collectSlurmArray(*config, *o);
            if (o->taskIndex >= o->taskCount) {
                throw Error("--task-index " + std::to_string(o->taskIndex) + " must be below --task-count " +
                            std::to_string(o->taskCount));
            }
            int failures = runExperiment(*config, *o);
            if (failures) {
                std::cerr << "bundlelab: " << failures << " task(s) failed (see error.txt in their folders)\n";
                return 1;
            }
            return 0;
        };
    });
}

void addReportCommand(CLI::App& app, Action& action) {
    auto dir = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("report", "plots, a self-contained HTML report and a Markdown summary of a run");
    cmd->add_option("results", *dir, "results directory written by `bundlelab run`")->required();
    cmd->callback([dir, &action] {
        action = [dir] {
            if (!std::filesystem::is_regular_file(std::filesystem::path(*dir) / "results.csv")) {
                throw Error(*dir + ": no results.csv (is it a directory written by `bundlelab run`?)");
            }
            const std::string script = std::string(BL_EXPERIMENTS_DIR) + "/report/report.py";
            // Debian's Python has matplotlib; a plain `python3` on PATH may be another one.
            const std::string command = "/usr/bin/python3 '" + script + "' '" + *dir + "'";
            int rc = std::system(command.c_str());
            if (rc != 0) {
                throw Error("report generation failed (" + command + ")");
            }
            return 0;
        };
    });
}

} // namespace bl::cli
