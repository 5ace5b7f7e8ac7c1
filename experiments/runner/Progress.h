// Progress of a run: a bar with ETA on a terminal, plain log lines otherwise (CI logs, pipes).
#pragma once

#include <cstddef>
#include <string>

namespace bl {

class Progress {
public:
    explicit Progress(std::size_t total);
    void taskDone(const std::string& name, double seconds);
    void finish();

private:
    std::size_t mTotal;
    std::size_t mDone = 0;
    double mSeconds = 0.0;
    bool mInteractive;
};

} // namespace bl
