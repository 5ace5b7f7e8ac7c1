// An experiment config (TOML; format in experiments/README.md) and the task grid it expands to.
// Everything is checked before any task runs: unknown keys, modes, parameters (with their types
// and ranges, for every grid point) and scenes are errors naming the file and line.
#pragma once

#include "config/Settings.h"
#include "modes/FrameSchedule.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace bl {

struct Budget {
    std::uint32_t iterations = 0; // 0: use seconds
    double seconds = 0.0;
};

struct SceneEntry {
    std::string name;
    std::string file;                    // absolute or relative to the working directory
    std::optional<glm::ivec2> resolution; // overrides the scene's camera
    std::string referenceFile;           // a given reference image, or "" (rendered)
    // Hash of everything the scene is loaded from (scene file, meshes, textures, environment) and
    // the resolution: editing any of them invalidates finished tasks and cached references.
    std::string fingerprint;
};

struct ReferenceSpec {
    bool enabled = false;
    std::uint32_t spp = 256;
    std::vector<std::pair<std::string, ParamValue>> settings; // of the reference mode
};

struct Task {
    std::uint32_t index = 0;
    std::string id;   // folder name: index, scene, label, parameters, seed
    std::string scene; // SceneEntry name
    std::string mode;
    std::string label;
    std::vector<std::pair<std::string, ParamValue>> settings; // fixed + this grid point
    std::vector<std::pair<std::string, ParamValue>> gridPoint; // the varying part only
    std::uint64_t seed = 0;
    Budget budget;
    std::vector<std::uint32_t> checkpoints; // iterations; empty with a time budget: powers of two
    // Frames of an animated scene, each run with the whole budget; frame 0 (scene time 0) is the
    // one checkpointed and judged against the reference.
    FrameSchedule frames;
    // Reference-mode settings this task is judged against (e.g. max_segments = 2 for methods that
    // compute direct light only): the experiment's, overridden by the mode's `reference` table.
    std::vector<std::pair<std::string, ParamValue>> referenceSettings;
    bool needsGpu = false;
    std::string hash; // of everything that determines the result
};

struct ExperimentConfig {
    std::string path;
    std::string name;
    std::vector<std::uint64_t> seeds{0};
    Budget budget;
    bool logCheckpoints = true;
    std::vector<std::uint32_t> checkpoints;
    FrameSchedule frames; // [experiment] frames, frame_rate
    ReferenceSpec reference;
    std::vector<SceneEntry> scenes;
    std::vector<Task> tasks;

    const SceneEntry& scene(const std::string& name) const;
};

// Parses and validates the config, and expands the grid into tasks (stable order and ids).
ExperimentConfig loadExperimentConfig(const std::string& path);

// Checkpoint iterations for a task with an iteration budget: powers of two up to it, and it.
std::vector<std::uint32_t> logCheckpoints(std::uint32_t iterations);

// FNV-1a 64-bit of a string, as 16 hex digits.
std::string hashText(const std::string& text);

} // namespace bl
