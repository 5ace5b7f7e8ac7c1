#include "runner/Progress.h"

#include <cstdio>
#include <unistd.h>

namespace bl {

namespace {
std::string duration(double s) {
    char buf[32];
    if (s >= 3600) std::snprintf(buf, sizeof(buf), "%dh%02dm", int(s / 3600), int(s / 60) % 60);
    else if (s >= 60) std::snprintf(buf, sizeof(buf), "%dm%02ds", int(s / 60), int(s) % 60);
    else std::snprintf(buf, sizeof(buf), "%.1fs", s);
    return buf;
}
} // namespace

Progress::Progress(std::size_t total) : mTotal(total), mInteractive(::isatty(2)) {}

void Progress::taskDone(const std::string& name, double seconds) {
    ++mDone;
    mSeconds += seconds;
    const double eta = mDone ? mSeconds / double(mDone) * double(mTotal - mDone) : 0.0;
    if (mInteractive) {
        const int width = 30;
        const int filled = mTotal ? int(width * mDone / mTotal) : width;
        std::fprintf(stderr, "\r[%s%s] %zu/%zu tasks, ETA %s  %-40.40s", std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), mDone, mTotal, duration(eta).c_str(), name.c_str());
    } else {
        std::fprintf(stderr, "[run] %zu/%zu %s (%s), ETA %s\n", mDone, mTotal, name.c_str(), duration(seconds).c_str(),
                     duration(eta).c_str());
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (mInteractive && mTotal) {
        std::fprintf(stderr, "\n");
    }
}

} // namespace bl
