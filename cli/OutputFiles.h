// Writes a render's results: linear EXR (radiance + AOV layers, run metadata as attributes), an
// sRGB PNG preview beside it, and a JSON record (settings, timings, device, environment).
#pragma once

#include "modes/Mode.h"

#include <string>

namespace bl::cli {

struct RenderRecord {
    std::string scene;
    std::string mode;
    std::string device;     // "" for CPU modes
    std::uint64_t seed = 0;
    double wallSeconds = 0.0;  // in iterate() only
    double setupSeconds = 0.0; // in Mode::setScene (upload, pipelines, precomputation)
    bool partial = false;   // an error stopped the render before its budget
    std::uint32_t frame = 0;   // of a frame schedule (0 for a still)
    double sceneTime = 0.0;    // scene time of the frame, seconds
};

// Returns the paths written (EXR, PNG, JSON).
std::vector<std::string> writeRenderOutputs(const std::string& exrPath, const ImageSet& images, const Mode& mode,
                                            const RenderRecord& record);

} // namespace bl::cli
