// Where and how a result was produced: recorded beside every output so numbers can be compared
// and reproduced (CPU, threads, build type, git revision; the GPU device is added by the caller).
#pragma once

#include <string>

namespace bl {

struct RunEnvironment {
    std::string cpu;
    unsigned hardwareThreads = 0;
    std::string buildType;
    std::string gitRevision;
    std::string version;
};

RunEnvironment currentRunEnvironment();

} // namespace bl
