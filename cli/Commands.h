// The subcommands of the bundlelab CLI. Each registers its options on the app and returns the
// action to run once parsing succeeded.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace bl::cli {

using Action = std::function<int()>;

void addRenderCommand(CLI::App& app, Action& action);
void addInfoCommand(CLI::App& app, Action& action);
void addModesCommand(CLI::App& app, Action& action);
void addPlanCommand(CLI::App& app, Action& action);
void addDevicesCommand(CLI::App& app, Action& action);
void addCompareCommand(CLI::App& app, Action& action);
void addStatsCommand(CLI::App& app, Action& action);
void addReplayCommand(CLI::App& app, Action& action);
void addBenchCommand(CLI::App& app, Action& action);
// `bench texels`, under `bench` (BenchTexelsCommand.cpp).
void addBenchTexelsCommand(CLI::App& bench, Action& action);
void addRunCommand(CLI::App& app, Action& action);
void addAtlasCommand(CLI::App& app, Action& action);
void addReportCommand(CLI::App& app, Action& action);
void addViewCommand(CLI::App& app, Action& action);

} // namespace bl::cli
