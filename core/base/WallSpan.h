// The host's wall-clock time of a span of work added to a PassTime when the span ends: what a pass
// costs as the host sees it (recording, submission, the wait, reading results back), reported
// beside the GPU timestamps as "NAME (wall)". Where the two differ the frame loses time on the host.
#pragma once

#include "base/PassTime.h"

#include <chrono>

namespace bl {

class WallSpan {
public:
    explicit WallSpan(PassTime& total) : mTotal(total), mStart(std::chrono::steady_clock::now()) {}
    ~WallSpan() {
        mTotal.totalMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
        ++mTotal.count;
    }
    WallSpan(const WallSpan&) = delete;
    WallSpan& operator=(const WallSpan&) = delete;

private:
    PassTime& mTotal;
    std::chrono::steady_clock::time_point mStart;
};

} // namespace bl
