// bundlelab replay SCENE --pixel X Y --sample K [--seed S] [--set k=v]: traces one reference
// sample alone and prints its path, to find where a NaN/Inf (or any odd value) comes from.
#include "base/Error.h"
#include "cli/Commands.h"
#include "modes/Registry.h"
#include "modes/reference/ReferenceMode.h"
#include "scene/SceneLoader.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace bl::cli {

void addReplayCommand(CLI::App& app, Action& action) {
    struct Options {
        std::string scene;
        std::vector<int> pixel;
        std::uint32_t sample = 0;
        std::uint32_t seed = 0;
        int width = 0, height = 0;
        std::vector<std::string> assignments;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("replay", "trace one sample of the reference mode and print its path");
    cmd->add_option("scene", o->scene, "scene file")->required();
    cmd->add_option("--pixel", o->pixel, "pixel column and row")->expected(2)->required();
    cmd->add_option("--sample", o->sample, "sample index (as reported for a bad sample)");
    cmd->add_option("--seed", o->seed, "run seed");
    cmd->add_option("--width", o->width, "image width used by the render")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", o->height, "image height used by the render")->check(CLI::Range(1, 16384));
    cmd->add_option("--set", o->assignments, "reference parameter key=value (repeatable)");
    cmd->callback([o, &action] {
        action = [o] {
            Scene scene = loadScene(o->scene);
            if (o->width > 0) scene.camera.resolution.x = o->width;
            if (o->height > 0) scene.camera.resolution.y = o->height;
            if (o->pixel[0] < 0 || o->pixel[1] < 0 || o->pixel[0] >= scene.camera.resolution.x ||
                o->pixel[1] >= scene.camera.resolution.y) {
                throw Error("--pixel " + std::to_string(o->pixel[0]) + " " + std::to_string(o->pixel[1]) +
                            " is outside the " + std::to_string(scene.camera.resolution.x) + "x" +
                            std::to_string(scene.camera.resolution.y) + " image");
            }
            std::unique_ptr<Mode> mode = createMode("reference", o->assignments);
            auto& reference = static_cast<ReferenceMode&>(*mode);
            reference.setScene(scene, nullptr);
            std::vector<std::string> log;
            PathSample s = reference.replay(o->pixel[0], o->pixel[1], o->sample, o->seed, log);
            for (const std::string& line : log) std::cout << line << "\n";
            glm::vec3 t = s.total();
            std::printf("radiance (%.6g, %.6g, %.6g)%s, %u rays\n", t.x, t.y, t.z, s.finite() ? "" : " NOT FINITE",
                        s.rays);
            return 0;
        };
    });
}

} // namespace bl::cli
