// bundlelab info | modes | plan | devices
#include "base/Error.h"
#include "cli/Commands.h"
#include "image/ImageIO.h"
#include "modes/Registry.h"
#include "modes/SettingTrades.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>

namespace bl::cli {

void addInfoCommand(CLI::App& app, Action& action) {
    auto path = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("info", "print what a scene contains (Scene::features)");
    cmd->add_option("scene", *path, "scene file (.toml, Mitsuba 3 .xml, or a bare .obj/.ply)")->required();
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
            for (const std::string& n : scene.importNotes) std::cout << "mapped           " << n << "\n";
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
                    for (std::size_t i = 0; i < p.choices.size(); ++i) {
                        std::cout << (i ? ", " : ": ") << p.choices[i];
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
    auto assignments = std::make_shared<std::vector<std::string>>();
    cmd->add_option("--set", *assignments, "mode parameter key=value (repeatable): the plan of those settings");
    cmd->callback([scenePath, modeName, assignments, &action] {
        action = [scenePath, modeName, assignments] {
            std::unique_ptr<Mode> mode = createMode(*modeName, *assignments);
            Scene scene = loadScene(*scenePath);
            for (const PlannedPass& p : mode->plan(scene)) {
                std::cout << (p.runs ? "  run   " : "  skip  ") << p.name << ": " << p.reason << "  [" << p.id << ": " << p.code
                          << "]\n";
            }
            // The same checks a render warns with, before any work (modes/SettingTrades.h).
            for (const std::string& w : settingTrades(*mode, scene)) std::cout << "  warn  " << w << "\n";
            return 0;
        };
    });
}

void addStatsCommand(CLI::App& app, Action& action) {
    auto path = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("stats", "print size, mean, min, max and non-finite pixels of every image layer");
    cmd->add_option("image", *path, "EXR, HDR or PNG")->required();
    cmd->callback([path, &action] {
        action = [path] {
            bool exr = std::filesystem::path(*path).extension() == ".exr";
            for (const std::string& layer : exr ? exrLayers(*path) : std::vector<std::string>{""}) {
                Image img = readImage(*path, layer);
                glm::dvec3 mean = img.mean();
                glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
                for (const glm::vec3& p : img.pixels()) {
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
                std::printf("%-10s %dx%d  mean %.6g %.6g %.6g  min %.4g  max %.4g  non-finite %zu\n",
                            layer.empty() ? "(rgb)" : layer.c_str(), img.width(), img.height(), mean.x, mean.y, mean.z,
                            std::min({lo.x, lo.y, lo.z}), std::max({hi.x, hi.y, hi.z}), img.countNonFinite());
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
