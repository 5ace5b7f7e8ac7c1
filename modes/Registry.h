// The one explicit table of modes (no self-registering statics: static libraries drop them).
#pragma once

#include "modes/Mode.h"

#include <memory>
#include <span>

namespace bl {

struct ModeEntry {
    std::string_view name;
    std::string_view summary;
    bool needsGpu;
    std::vector<ParamSpec> (*parameters)();
    std::unique_ptr<Mode> (*create)(const Settings& settings);
};

std::span<const ModeEntry> modeRegistry();
// Throws bl::Error listing the available modes when `name` is unknown.
const ModeEntry& findMode(std::string_view name);
// A mode with default settings overridden by "key=value" assignments.
std::unique_ptr<Mode> createMode(std::string_view name, const std::vector<std::string>& assignments = {});

} // namespace bl
