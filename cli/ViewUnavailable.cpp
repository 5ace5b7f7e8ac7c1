// `bundlelab view` in a build without GLFW: the command exists and says what it needs.
#include "base/Error.h"
#include "cli/Commands.h"

namespace bl::cli {

void addViewCommand(CLI::App& app, Action& action) {
    CLI::App* cmd = app.add_subcommand("view", "a window on one mode (not in this build: it needs GLFW)");
    cmd->allow_extras();
    cmd->callback([&action] {
        action = [] () -> int {
            throw Error("this bundlelab was built without GLFW, so `view` is unavailable: install libglfw3-dev "
                        "(scripts/install-deps.sh does) and rebuild");
        };
    });
}

} // namespace bl::cli
