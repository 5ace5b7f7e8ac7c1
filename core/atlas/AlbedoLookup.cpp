#include "atlas/AlbedoLookup.h"

#include "base/Error.h"
#include "image/BilinearLookup.h"

#include <array>

namespace bl::atlas {

namespace {

constexpr int kByteValues = 256;

Image decodeSrgb(const Rgba8Image& encoded) {
    // 8-bit inputs have 256 values: decode each once.
    std::array<float, kByteValues> linear{};
    for (int i = 0; i < kByteValues; ++i) linear[std::size_t(i)] = srgbToLinear(float(i) / float(kByteValues - 1));
    Image img(encoded.width, encoded.height);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        for (int c = 0; c < 3; ++c) img.pixels()[i][c] = linear[encoded.texels[4 * i + std::size_t(c)]];
    }
    return img;
}

} // namespace

AlbedoLookup::AlbedoLookup(const Scene& scene) : mScene(&scene) {
    for (const Texture& t : scene.textures) mLinearTextures.push_back(decodeSrgb(t.image));
}

glm::vec3 AlbedoLookup::at(std::uint32_t material, glm::vec2 uv) const {
    if (material >= mScene->materials.size()) {
        throw Error("albedo lookup: material " + std::to_string(material) + " out of range (the scene has " +
                    std::to_string(mScene->materials.size()) + ")");
    }
    const Material& m = mScene->materials[material];
    if (m.albedoTexture < 0) return m.albedo;
    // OBJ texture coordinates have v = 0 at the bottom; image row 0 is the top.
    return bilinearLookup(mLinearTextures.at(std::size_t(m.albedoTexture)), {uv.x, 1.0f - uv.y}, Wrap::Repeat,
                          Wrap::Repeat);
}

} // namespace bl::atlas
