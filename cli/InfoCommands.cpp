// bundlelab info | modes | plan | devices
#include "base/Error.h"
#include "cli/Commands.h"
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <iostream>
#include <memory>

namespace bl::cli {

void addInfoCommand(CLI::App& app, Action& action) {
    auto path = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("info", "print what a scene contains (Scene::features)");
    cmd->add_option("scene", *path, "scene file (.toml, or a bare .obj/.ply)")->required();
    cmd->callback([path, &action] {
        action = [path] {
            Scene scene = loadScene(*path);
            const Camera& c = scene.camera;
            std::cout << "scene            " << *path << "\n"
                      << scene.features().describe() << "camera           " << c.resolution.x << "x"
                      << c.resolution.y << ", fov " << c.fovDegrees << " deg (" << (c.fovAxis == FovAxis::X ? "x" : "y")
                      << ")\n"
                      << "dropped          " << scene.loadStats.degenerateTriangles << " degenerate, "
                      << scene.loadStats.duplicateTriangles << " duplicate triangles\n";
            return 0;
        };
    });
}

void addModesCommand(CLI::App& app, Action& action) {
    CLI::App* cmd = app.add_subcommand("modes", "list every mode with its parameters, defaults and units");
    cmd->callback([&action] {
        action = [] {
            for (const ModeEntry& e : modeRegistry()) {
                std::cout << e.name << (e.needsGpu ? " (Vulkan)" : " (CPU)") << ": " << e.summary << "\n";
                for (const ParamSpec& p : e.parameters()) {
                    std::cout << "    " << p.key << " = " << formatValue(p.defaultValue);
                    if (!p.unit.empty()) std::cout << " " << p.unit;
                    std::cout << "  (" << typeName(p.defaultValue);
                    if (p.defaultValue.index() == 1 || p.defaultValue.index() == 2) {
                        std::cout << " in [" << formatNumber(p.min) << ", " << formatNumber(p.max) << "]";
                    }
                    std::cout << ")  " << p.help << "\n";
                }
            }
            return 0;
        };
    });
}

void addPlanCommand(CLI::App& app, Action& action) {
    auto scenePath = std::make_shared<std::string>();
    auto modeName = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("plan", "print a mode's pass plan for a scene, with the reason for each pass");
    cmd->add_option("scene", *scenePath, "scene file")->required();
    cmd->add_option("-m,--mode", *modeName, "mode")->required();
    cmd->callback([scenePath, modeName, &action] {
        action = [scenePath, modeName] {
            std::unique_ptr<Mode> mode = createMode(*modeName);
            Scene scene = loadScene(*scenePath);
            for (const PlannedPass& p : mode->plan(scene)) {
                std::cout << (p.runs ? "  run   " : "  skip  ") << p.name << ": " << p.reason << "\n";
            }
            return 0;
        };
    });
}

void addDevicesCommand(CLI::App& app, Action& action) {
    CLI::App* cmd = app.add_subcommand("devices", "list Vulkan 1.3 devices (for --device)");
    cmd->callback([&action] {
        action = [] {
            for (const vk::DeviceInfo& d : vk::Context::listDevices()) {
                std::cout << d.index << ": " << d.describe() << "\n";
            }
            return 0;
        };
    });
}

} // namespace bl::cli
