#include "runner/SlurmArray.h"

#include "base/Error.h"
#include "base/Log.h"
#include "runner/FileUtil.h"
#include "runner/ReferenceCache.h"
#include "runner/Subprocess.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace bl {

namespace {

struct Paths {
    // The config as the user named it: the elements run from the same directory (--chdir), and a
    // task's hash covers its scene files' paths as the config resolves them.
    std::string config;
    std::string outDir, slurmDir, binary, jobName;
};

Paths pathsOf(const ExperimentConfig& config, const std::string& configPath, const RunOptions& run) {
    Paths p;
    p.config = configPath;
    // One spelling per directory (trailing separators, "..", symlinks): its hash names the jobs.
    fs::path out = fs::weakly_canonical(fs::absolute(resultsDirectory(config, run)));
    if (!out.has_filename()) out = out.parent_path();
    p.outDir = out.string();
    p.slurmDir = (fs::path(p.outDir) / "slurm").string();
    std::error_code ec;
    p.binary = fs::read_symlink("/proc/self/exe", ec).string();
    if (ec || p.binary.empty()) {
        throw Error("cannot find the bundlelab binary's own path (/proc/self/exe) for the job script");
    }
    // One name per results directory: the queue then tells which jobs write into it. Only
    // characters that neither sbatch nor squeue --name (a comma-separated list) read specially.
    std::string name;
    for (char c : config.name) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
    p.jobName = "bl-" + name + "-" + hashText(p.outDir).substr(0, 8);
    return p;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
        if (!l.empty()) out.push_back(l);
    }
    return out;
}

// The queue's lines ("12_3 RUNNING", "12_[4-9%2] PENDING") for this directory's jobs.
std::vector<std::string> queuedJobs(const std::string& jobName) {
    const std::vector<std::string> argv{"squeue", "--noheader", "--name=" + jobName, "--format=%i %T"};
    const CommandOutput o = runCommand(argv);
    if (o.exitStatus == 127) {
        throw Error("squeue not found: --slurm and --collect need the Slurm client commands on PATH (a login node; "
                    "Debian: slurm-client)");
    }
    if (o.exitStatus != 0) {
        throw Error("cannot ask the Slurm queue (" + describeCommand(argv) + " exited with " +
                    std::to_string(o.exitStatus) + "): " + o.output);
    }
    return lines(o.output);
}

std::string submit(const std::vector<std::string>& options, const std::string& script) {
    std::vector<std::string> argv{"sbatch", "--parsable"};
    argv.insert(argv.end(), options.begin(), options.end());
    argv.push_back(script);
    const CommandOutput o = runCommand(argv);
    // --parsable prints "JOBID" or "JOBID;CLUSTER" on a line of its own; a site's plugins may print
    // other lines (stderr is in the same output): the last line of that form is the id.
    std::string id;
    for (const std::string& l : lines(o.output)) {
        std::string digits;
        std::size_t i = 0;
        while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i]))) digits += l[i++];
        if (!digits.empty() && (i == l.size() || l[i] == ';')) id = digits;
    }
    if (o.exitStatus != 0 || id.empty()) {
        throw Error("sbatch refused " + script + " (" + describeCommand(argv) + " exited with " +
                    std::to_string(o.exitStatus) + "): " + o.output);
    }
    return id;
}

std::string runLine(const Paths& p, const RunOptions& run, const std::string& slice) {
    std::string line = shellQuote(p.binary) + " run " + shellQuote(p.config) + " --out " + shellQuote(p.outDir) + slice;
    if (!run.device.empty()) line += " --device " + shellQuote(run.device);
    if (run.validation) line += " --validation";
    return line;
}

// The sbatch options of a job of this directory. Passed on sbatch's command line (each one argument,
// so paths with spaces hold); `%` in the log directory is Slurm's pattern character and is doubled
// before `pattern` ("%j.out", "%A_%a.out") is appended. `perElement`: the array's --time and extra
// options (the reference job gets the partition only: it renders on the CPU, one reference after
// another, with the partition's time limit).
std::vector<std::string> jobOptions(const Paths& p, const SlurmOptions& slurm, const std::string& pattern, bool perElement) {
    std::string logs;
    for (char c : (fs::path(p.slurmDir) / "logs").string()) logs += c == '%' ? std::string("%%") : std::string(1, c);
    std::vector<std::string> o{"--job-name=" + p.jobName, "--chdir=" + fs::current_path().string(),
                               "--output=" + logs + "/" + pattern};
    if (!slurm.partition.empty()) o.push_back("--partition=" + slurm.partition);
    if (perElement) {
        if (!slurm.time.empty()) o.push_back("--time=" + slurm.time);
        o.insert(o.end(), slurm.sbatchArgs.begin(), slurm.sbatchArgs.end());
    }
    return o;
}

std::string header(const Paths& p, const std::string& what, const std::vector<std::string>& options) {
    std::string s = "#!/bin/bash\n# Written by `bundlelab run " + p.config + " --slurm`: " + what + "\n";
    s += "# Submitted as: sbatch";
    for (const std::string& o : options) s += " " + shellQuote(o);
    return s + " THIS_SCRIPT\n";
}

int nextSubmission(const std::string& slurmDir) {
    int k = 1;
    while (fs::exists(fs::path(slurmDir) / ("submit-" + std::to_string(k) + ".sbatch"))) ++k;
    return k;
}

void appendRecord(const std::string& slurmDir, const std::string& line) {
    std::ofstream out(fs::path(slurmDir) / "submissions.tsv", std::ios::app);
    out << line << "\n";
    if (!out) {
        throw Error((fs::path(slurmDir) / "submissions.tsv").string() + ": cannot write");
    }
}

// The log of each task's latest array element, from submissions.tsv.
std::map<std::string, std::string> latestLogs(const std::string& slurmDir) {
    std::map<std::string, std::string> logs;
    std::string text;
    readFileIfExists((fs::path(slurmDir) / "submissions.tsv").string(), text);
    for (const std::string& l : lines(text)) {
        std::istringstream in(l);
        std::string job, element, index, id;
        if (std::getline(in, job, '\t') && std::getline(in, element, '\t') && std::getline(in, index, '\t') &&
            std::getline(in, id, '\t')) {
            const std::string name = element == "-" ? job + ".out" : job + "_" + element + ".out";
            logs[id] = (fs::path(slurmDir) / "logs" / name).string();
        }
    }
    return logs;
}

std::string arraySpec(std::size_t count, int maxParallel) {
    std::string spec = count == 1 ? "0" : "0-" + std::to_string(count - 1);
    if (maxParallel > 0) spec += "%" + std::to_string(maxParallel);
    return spec;
}

} // namespace

int submitSlurmArray(const std::string& configPath, const RunOptions& run, const SlurmOptions& slurm) {
    const ExperimentConfig config = loadExperimentConfig(configPath);
    const Paths p = pathsOf(config, configPath, run);
    const std::vector<std::string> queued = queuedJobs(p.jobName);
    if (!queued.empty()) {
        std::string list;
        for (const std::string& q : queued) list += "\n  " + q;
        throw Error(p.outDir + ": " + std::to_string(queued.size()) + " job line(s) named " + p.jobName +
                    " are still in the Slurm queue; submitting again could run a task twice. Wait for them (or scancel "
                    "them) and run the same command again:" + list);
    }
    const std::vector<UnfinishedTask> unfinished = collectResults(config, p.outDir);
    if (unfinished.empty()) {
        std::printf("%s: all %zu tasks finished; nothing to submit (results: %s/results.csv)\n", config.name.c_str(),
                    config.tasks.size(), p.outDir.c_str());
        return 0;
    }
    fs::create_directories(fs::path(p.slurmDir) / "logs");
    std::string text;
    readFileIfExists(configPath, text);
    writeFileAtomic((fs::path(p.outDir) / "experiment.toml").string(), text);
    const int k = nextSubmission(p.slurmDir);
    const std::string logs = (fs::path(p.slurmDir) / "logs").string();

    // References not cached yet: one job renders them; the array waits for it (and is dropped by
    // the scheduler if it fails, instead of every element rendering its own).
    std::vector<const Task*> pendingTasks;
    for (const UnfinishedTask& u : unfinished) pendingTasks.push_back(&config.tasks[u.index]);
    const std::size_t references = ReferenceCache(config, p.outDir).toRender(pendingTasks);
    std::vector<std::string> arrayOptions;
    std::string referenceJob;
    if (references) {
        const std::string script = (fs::path(p.slurmDir) / ("references-" + std::to_string(k) + ".sbatch")).string();
        const std::vector<std::string> options = jobOptions(p, slurm, "%j.out", false);
        std::string s = header(p, "the references the array's tasks are judged against", options);
        s += "\nexec " + runLine(p, run, " --references-only") + "\n";
        writeFileAtomic(script, s);
        referenceJob = submit(options, script);
        appendRecord(p.slurmDir, referenceJob + "\t-\t-\treferences");
        arrayOptions = {"--dependency=afterok:" + referenceJob, "--kill-on-invalid-dep=yes"};
    }

    const std::string script = (fs::path(p.slurmDir) / ("submit-" + std::to_string(k) + ".sbatch")).string();
    std::vector<std::string> options = jobOptions(p, slurm, "%A_%a.out", true);
    options.push_back("--array=" + arraySpec(unfinished.size(), slurm.maxParallel));
    options.insert(options.end(), arrayOptions.begin(), arrayOptions.end());
    std::string s = header(p, "one array element per unfinished task (" + std::to_string(unfinished.size()) + " of " +
                                  std::to_string(config.tasks.size()) + ")", options);
    s += "\n# Element -> task index; each element is an ordinary slice run: it skips a finished task and\n"
         "# redoes a half-written one, so resubmitting is always safe.\ntasks=(";
    for (std::size_t i = 0; i < unfinished.size(); ++i) s += (i ? " " : "") + std::to_string(unfinished[i].index);
    s += ")\ntask=${tasks[$SLURM_ARRAY_TASK_ID]}\n";
    s += "echo \"bundlelab: array element $SLURM_ARRAY_TASK_ID runs task $task on $(hostname)\"\n";
    s += "exec " + runLine(p, run, " --task-index \"$task\" --task-count " + std::to_string(config.tasks.size())) + "\n";
    writeFileAtomic(script, s);
    std::string job;
    try {
        job = submit(options, script);
    } catch (const Error& e) {
        // The reference job would otherwise stay queued with nothing waiting for it, and its
        // name would refuse every later submission until it ends.
        if (!referenceJob.empty()) runCommand({"scancel", referenceJob});
        if (unfinished.size() > 1000) {
            throw Error(std::string(e.what()) + " (" + std::to_string(unfinished.size()) +
                        " elements: more than a cluster's MaxArraySize allows? see `scontrol show config`)");
        }
        throw;
    }
    for (std::size_t i = 0; i < unfinished.size(); ++i) {
        appendRecord(p.slurmDir, job + "\t" + std::to_string(i) + "\t" + std::to_string(unfinished[i].index) + "\t" +
                                     unfinished[i].id);
    }
    std::printf("%s: submitted job %s, %zu of %zu tasks (array %s)%s\n", config.name.c_str(), job.c_str(),
                unfinished.size(), config.tasks.size(), arraySpec(unfinished.size(), slurm.maxParallel).c_str(),
                referenceJob.empty() ? "" : (", after reference job " + referenceJob).c_str());
    std::printf("script %s, logs %s\nwhen the queue is empty: bundlelab run %s --out %s --collect\n", script.c_str(),
                logs.c_str(), configPath.c_str(), p.outDir.c_str());
    return 0;
}

int collectSlurmArray(const std::string& configPath, const RunOptions& run) {
    const ExperimentConfig config = loadExperimentConfig(configPath);
    const Paths p = pathsOf(config, configPath, run);
    if (!fs::is_directory(p.outDir)) {
        throw Error(p.outDir + ": no results directory (run the config first)");
    }
    const std::vector<UnfinishedTask> unfinished = collectResults(config, p.outDir);
    // Each element wrote environment.json with its own device (none for a CPU task): the merged
    // run names every device its tasks used, as a local run does.
    writeRunEnvironment(config, configPath, devicesOfTasks(config, p.outDir), 1, p.outDir);
    const bool submitted = fs::is_regular_file(fs::path(p.slurmDir) / "submissions.tsv");
    std::vector<std::string> queued;
    if (submitted) {
        try {
            queued = queuedJobs(p.jobName);
        } catch (const Error& e) {
            log::warn(std::string(e.what()) + " (the list below may include tasks still running)");
        }
    }
    std::printf("%s: %zu of %zu tasks finished; %s/results.csv rewritten\n", config.name.c_str(),
                config.tasks.size() - unfinished.size(), config.tasks.size(), p.outDir.c_str());
    const std::map<std::string, std::string> logs = latestLogs(p.slurmDir);
    std::vector<const Task*> all;
    for (const Task& t : config.tasks) all.push_back(&t);
    if (const auto ref = logs.find("references");
        ref != logs.end() && !unfinished.empty() && ReferenceCache(config, p.outDir).toRender(all) > 0) {
        // The array waits for the reference job; without its references no element ran.
        std::printf("  references not rendered yet (the array waits for them): see %s\n", ref->second.c_str());
    }
    for (const UnfinishedTask& u : unfinished) {
        const auto log = logs.find(u.id);
        const std::string where = log == logs.end() ? "" : " (log: " + log->second + ")";
        if (!u.error.empty()) {
            std::printf("  failed     %s: %s%s\n", u.id.c_str(), u.error.c_str(), where.c_str());
        } else {
            std::printf("  unfinished %s: killed, timed out, still running or never run%s\n", u.id.c_str(), where.c_str());
        }
    }
    if (!queued.empty()) {
        std::printf("%zu job line(s) of this directory still in the queue (%s ...): collect again when they finish\n",
                    queued.size(), queued.front().c_str());
    } else if (!unfinished.empty() && submitted) {
        std::printf("run `bundlelab run %s --out %s --slurm ...` again to resubmit the %zu unfinished task(s)\n",
                    configPath.c_str(), p.outDir.c_str(), unfinished.size());
    }
    return unfinished.empty() ? 0 : 1;
}

} // namespace bl
