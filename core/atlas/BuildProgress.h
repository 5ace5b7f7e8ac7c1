// The atlas build's progress: a long build says how far it is every few seconds (a 1M-triangle
// scene takes tens of seconds, most of them packing), instead of nothing until the end.
#pragma once

#include "base/Log.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

namespace bl {

class ProgressLog {
public:
    void say(const std::function<std::string()>& where) {
        const auto now = std::chrono::steady_clock::now();
        if (now - mLast < std::chrono::seconds(5)) return;
        mLast = now;
        char seconds[32];
        std::snprintf(seconds, sizeof(seconds), "%.0f s", std::chrono::duration<double>(now - mStart).count());
        log::info("atlas: " + where() + " (" + seconds + ")");
    }

private:
    std::chrono::steady_clock::time_point mStart = std::chrono::steady_clock::now(), mLast = mStart;
};

} // namespace bl
