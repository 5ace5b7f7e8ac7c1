#include "runner/Subprocess.h"

#include <cstdio>
#include <sys/wait.h>

namespace bl {

std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return out + "'";
}

std::string describeCommand(const std::vector<std::string>& argv) {
    std::string s;
    for (const std::string& a : argv) s += (s.empty() ? "" : " ") + a;
    return s;
}

CommandOutput runCommand(const std::vector<std::string>& argv) {
    std::string line;
    for (const std::string& a : argv) line += (line.empty() ? "" : " ") + shellQuote(a);
    line += " 2>&1";
    CommandOutput result;
    FILE* pipe = ::popen(line.c_str(), "r");
    if (!pipe) {
        result.output = "cannot start a shell";
        return result;
    }
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) result.output.append(buffer, n);
    const int status = ::pclose(pipe);
    // The shell answers 127 for a program it cannot find.
    result.exitStatus = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
    return result;
}

} // namespace bl
