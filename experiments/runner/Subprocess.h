// Runs an external program (sbatch, squeue) and captures what it prints: the cluster backend's
// only way to talk to the scheduler, so its failures carry the command and its output.
#pragma once

#include <string>
#include <vector>

namespace bl {

struct CommandOutput {
    int exitStatus = -1; // the program's exit status; -1 when it could not be started or was killed
    std::string output;  // stdout and stderr together
};

// argv[0] is looked up on PATH; every argument is passed verbatim (quoted for the shell).
CommandOutput runCommand(const std::vector<std::string>& argv);

// The argument as one single-quoted word of a POSIX shell.
std::string shellQuote(const std::string& text);

// "prog arg1 arg2" as it would be typed, for error messages.
std::string describeCommand(const std::vector<std::string>& argv);

} // namespace bl
