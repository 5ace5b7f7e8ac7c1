// The albedo of a material at a material texture coordinate, on the host, as the G-buffer pass
// samples it (CONVENTIONS.md): the albedo texture when the material has one (8-bit sRGB decoded
// with the exact curve, bilinear between texel centres, repeat wrap, (u, v) = (0, 0) at the image's
// bottom-left), else the flat albedo. The atlas stores it per texel for the `atlas` mode.
#pragma once

#include "image/Image.h"
#include "scene/Scene.h"

#include <vector>

namespace bl::atlas {

class AlbedoLookup {
public:
    // Decodes every texture of `scene` once; the lookup keeps a pointer to `scene`'s materials.
    explicit AlbedoLookup(const Scene& scene);

    // Throws bl::Error naming the material when it is out of range.
    glm::vec3 at(std::uint32_t material, glm::vec2 uv) const;

private:
    const Scene* mScene;
    std::vector<Image> mLinearTextures; // Scene::textures decoded to linear RGB
};

} // namespace bl::atlas
