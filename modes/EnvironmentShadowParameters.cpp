#include "modes/EnvironmentShadowParameters.h"

namespace bl {

std::vector<ParamSpec> withEnvironmentShadowParameters(std::vector<ParamSpec> params, const std::string& perWhat,
                                                       const std::string& use) {
    // At most 256 directions: each is one layer of an image array, which devices hold to 2048 layers.
    params.insert(params.end(), {
        {kEnvironmentShotsKey, std::int64_t{4}, "directions",
         "directions toward the environment per " + perWhat +
             ", drawn by its importance (luminance), each an orthographic depth map over the scene (a directional "
             "shadow map): " +
             use,
         0, 256, {}},
        {kEnvironmentShadowResolutionKey, std::int64_t{512}, "texels",
         "side of each environment direction's depth map (over the scene's bounding sphere)", 16, 8192, {}},
    });
    return params;
}

} // namespace bl
