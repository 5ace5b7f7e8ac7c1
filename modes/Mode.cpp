#include "modes/Mode.h"

namespace bl {

std::vector<std::string> lightsLeftOut(const Mode& mode, const Scene& scene) {
    std::vector<std::string> out;
    for (const PlannedPass& p : mode.plan(scene)) {
        if (p.lightLeftOut) {
            out.push_back(std::string(mode.name()) + ": the scene's " + p.name + " is left out of the image (" +
                          p.reason + ")");
        }
    }
    return out;
}

} // namespace bl
