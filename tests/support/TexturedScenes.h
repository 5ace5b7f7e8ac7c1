// Textures for tests of textured albedo: a planar texture on one mesh of a loaded scene.
#pragma once

#include "scene/Scene.h"

#include <string>

namespace bl::test {

// Gives every mesh whose name contains `meshName` `texture` (a new material, the mesh's own
// otherwise), u running along world x and v along world z over the mesh's extent, both [0, 1].
// False when no mesh matched.
bool texturePlanar(Scene& s, const std::string& meshName, const Rgba8Image& texture);

// A 64 x 2 texture: red where u < 1/2, green beyond, almost no blue (sRGB bytes 230/60/20).
Rgba8Image redGreenTexture();

} // namespace bl::test
