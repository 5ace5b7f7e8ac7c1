// The plan entry of the point and spot lights' shadow cubes (gpu/ShadowCubePass.h), one for every
// mode that renders them per frame: they run where the scene has such lights, once for a static
// scene and every frame of an animated one (the pass's own refresh rule, said in the plan).
#pragma once

#include "modes/PassPlan.h"
#include "scene/SceneFeatures.h"

#include <string>

namespace bl {

inline constexpr const char* kPassLightShadowCubes = "light-shadow-cubes";

// `lookups` says where the cubes are read ("" or " at every path vertex"), `frame` what a mode
// calls its unit of work ("frame", "iteration").
inline PlannedPass lightShadowCubesPass(const SceneFeatures& f, const std::string& lookups, const std::string& frame) {
    const bool lights = f.shadowCastingLights() > 0;
    return {kPassLightShadowCubes, "light shadow cubes", lights,
            !lights ? "no-point-or-spot-lights" : f.animated ? "every-frame-animated" : "once-static",
            lights ? std::to_string(f.shadowCastingLights()) + " light(s) x 6 faces" + lookups + "; " +
                         (f.animated ? "every " + frame + " (animated scene)" : std::string("once (static scene)"))
                   : "no point or spot lights"};
}

} // namespace bl
