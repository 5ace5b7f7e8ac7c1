// bundlelab: global illumination with global ray-bundles. See README.md for the commands.
#include "base/Error.h"
#include "base/Log.h"
#include "cli/Commands.h"

#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"bundlelab: a research toolkit for global illumination with global ray-bundles"};
    app.require_subcommand(1);
    bool verbose = false;
    app.add_flag("-v,--verbose", verbose, "print debug messages");
    bl::cli::Action action;
    bl::cli::addRenderCommand(app, action);
    bl::cli::addInfoCommand(app, action);
    bl::cli::addModesCommand(app, action);
    bl::cli::addPlanCommand(app, action);
    bl::cli::addDevicesCommand(app, action);
    bl::cli::addCompareCommand(app, action);
    bl::cli::addStatsCommand(app, action);
    bl::cli::addReplayCommand(app, action);
    bl::cli::addBenchCommand(app, action);
    bl::cli::addRunCommand(app, action);
    bl::cli::addAtlasCommand(app, action);
    bl::cli::addReportCommand(app, action);
    bl::cli::addViewCommand(app, action);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    if (verbose) {
        bl::log::setLevel(bl::log::Level::Debug);
    }
    try {
        return action ? action() : 0;
    } catch (const std::exception& e) {
        std::cerr << "bundlelab: error: " << e.what() << "\n";
        return 1;
    }
}
