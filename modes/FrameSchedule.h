// An animated scene rendered as a sequence of frames: frame f shows the scene at time
// startTime + f / frameRate. Each frame is its own progressive estimate (the CLI's `render
// --frames` and the experiment runner's `frames` key drive it; see README and
// experiments/README.md).
#pragma once

#include "base/Error.h"
#include "modes/Mode.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace bl {

// Film's 24 frames per second: a common default for scene-time animation.
inline constexpr double kDefaultFrameRate = 24.0;
// Frame numbers in file names have at least this many digits, so names sort in frame order.
inline constexpr int kFrameNumberDigits = 4;

struct FrameSchedule {
    std::uint32_t frames = 1;
    double frameRate = kDefaultFrameRate; // frames per second of scene time
    double startTime = 0.0;               // scene time of frame 0, seconds

    // Throws bl::Error naming `where` and the value when the schedule cannot be run.
    void validate(const std::string& where) const {
        if (frames < 1) {
            throw Error(where + ": frames = " + std::to_string(frames) + ": at least 1");
        }
        if (!std::isfinite(frameRate) || !(frameRate > 0.0)) {
            throw Error(where + ": frame rate " + std::to_string(frameRate) + " must be a positive finite number");
        }
        if (!std::isfinite(startTime)) {
            throw Error(where + ": start time must be finite");
        }
    }

    double timeOf(std::uint32_t frame) const { return startTime + double(frame) / frameRate; }

    // The iterate() arguments for iteration `index` of `frame`.
    IterationInfo iteration(std::uint32_t frame, std::uint32_t index, std::uint64_t seed) const {
        IterationInfo info;
        info.index = index;
        info.seed = seed;
        info.frame = frame;
        info.time = timeOf(frame);
        info.previousTime = frame > 0 ? timeOf(frame - 1) : info.time;
        return info;
    }
};

// DIR/NAME.EXT -> DIR/NAME.frame0003.EXT: one file per frame beside where a single image would go.
inline std::string framePath(const std::string& path, std::uint32_t frame) {
    const std::filesystem::path p(path);
    char number[32];
    std::snprintf(number, sizeof(number), ".frame%0*u", kFrameNumberDigits, frame);
    return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

} // namespace bl
