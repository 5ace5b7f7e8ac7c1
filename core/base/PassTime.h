// Time spent in one named pass, summed over its executions (GPU timestamps or CPU wall clock; the
// latter are named "... (wall)": base/WallSpan.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bl {

struct PassTime {
    std::string name;
    double totalMs = 0.0;
    unsigned count = 0;
    double meanMs() const { return count ? totalMs / count : 0.0; }
};

using PassTimes = std::vector<PassTime>;

// A host wall-clock span (base/WallSpan.h) around GPU passes, which a sum of GPU time must skip.
inline bool isWallTime(const PassTime& p) {
    constexpr std::string_view suffix = " (wall)";
    return p.name.size() >= suffix.size() && p.name.compare(p.name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The GPU milliseconds of a pass list: the timestamped passes, not the wall spans around them.
inline double gpuMilliseconds(const PassTimes& passes) {
    double total = 0.0;
    for (const PassTime& p : passes) total += isWallTime(p) ? 0.0 : p.totalMs;
    return total;
}

} // namespace bl
