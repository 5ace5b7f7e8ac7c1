#include "modes/EmitterPointParameters.h"

namespace bl {

std::vector<ParamSpec> withEmitterPointParameters(std::vector<ParamSpec> params, const std::string& perWhat,
                                                  const std::string& use, std::int64_t fewestPoints) {
    // At most 256 points: each is 6 layers of one image array, which devices hold to 2048 layers.
    // Default 4: the points' error is a small part of every mode's at equal time, so fewer points
    // buy iterations (area-lit Cornell box, 64^2, 10 s, lavapipe, 2026-11-29: relMSE 1.2-1.5x lower
    // than with 16 in atlas, multibounce and bidir; README, "Emitter points").
    params.insert(params.end(), {
        {kEmitterPointsKey, std::int64_t{4}, "points",
         "points drawn on the area emitters per " + perWhat + ", by power, each shadowed by a cube (at most 256): " +
             use,
         double(fewestPoints), 256, {}},
        {kEmitterShadowResolutionKey, std::int64_t{256}, "texels", "side of each emitter point's shadow cube face", 16,
         4096, {}},
    });
    return params;
}

} // namespace bl
