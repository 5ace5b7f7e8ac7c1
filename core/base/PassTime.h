// Time spent in one named pass, summed over its executions (GPU timestamps or CPU wall clock).
#pragma once

#include <string>
#include <vector>

namespace bl {

struct PassTime {
    std::string name;
    double totalMs = 0.0;
    unsigned count = 0;
    double meanMs() const { return count ? totalMs / count : 0.0; }
};

using PassTimes = std::vector<PassTime>;

} // namespace bl
