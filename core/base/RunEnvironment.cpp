#include "base/RunEnvironment.h"

#include <fstream>
#include <thread>

#ifndef BL_BUILD_TYPE
#define BL_BUILD_TYPE "unknown"
#endif
#ifndef BL_GIT_REVISION
#define BL_GIT_REVISION "unknown"
#endif
#ifndef BL_VERSION
#define BL_VERSION "unknown"
#endif

namespace bl {

RunEnvironment currentRunEnvironment() {
    RunEnvironment env;
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0) {
            auto colon = line.find(':');
            env.cpu = colon == std::string::npos ? line : line.substr(colon + 2);
            break;
        }
    }
    env.hardwareThreads = std::thread::hardware_concurrency();
    env.buildType = BL_BUILD_TYPE;
    env.gitRevision = BL_GIT_REVISION;
    env.version = BL_VERSION;
    return env;
}

} // namespace bl
