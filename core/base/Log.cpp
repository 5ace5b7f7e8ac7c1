#include "base/Log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace bl::log {
namespace {
std::atomic<Level> gLevel{Level::Info};
std::mutex gMutex;
} // namespace

void setLevel(Level l) { gLevel = l; }
Level level() { return gLevel; }

void write(Level l, std::string_view message) {
    if (l < gLevel) {
        return;
    }
    static constexpr const char* kPrefix[] = {"debug", "info", "warning", "error"};
    std::lock_guard lock(gMutex);
    std::fprintf(stderr, "[%s] %.*s\n", kPrefix[static_cast<int>(l)], static_cast<int>(message.size()),
                 message.data());
}

} // namespace bl::log
