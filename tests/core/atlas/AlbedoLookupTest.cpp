// The host albedo lookup follows the texture conventions (CONVENTIONS.md) the G-buffer's sampler
// follows: exact sRGB decoding, bilinear between texel centres, repeat wrap, (0, 0) = bottom-left.
#include "atlas/AlbedoLookup.h"
#include "base/Error.h"

#include <gtest/gtest.h>

using namespace bl;
using namespace bl::atlas;

namespace {

// A 2x2 texture, row 0 at the top: top-left, top-right, bottom-left, bottom-right.
Scene texturedScene() {
    Scene s;
    Material flat;
    flat.albedo = glm::vec3(0.25f, 0.5f, 0.75f);
    Material textured;
    textured.albedoTexture = 0;
    s.materials = {flat, textured};
    Texture t;
    t.image = Rgba8Image{2, 2, {255, 0, 0, 255, /**/ 0, 255, 0, 255, /**/ 0, 0, 255, 255, /**/ 128, 128, 128, 255}};
    s.textures = {t};
    return s;
}

constexpr float kTolerance = 1e-6f;

void expectNear(glm::vec3 a, glm::vec3 b) {
    EXPECT_NEAR(a.x, b.x, kTolerance);
    EXPECT_NEAR(a.y, b.y, kTolerance);
    EXPECT_NEAR(a.z, b.z, kTolerance);
}

} // namespace

TEST(AlbedoLookup, TextureConventions) {
    Scene s = texturedScene();
    AlbedoLookup lookup(s);
    expectNear(lookup.at(0, {0.3f, 0.9f}), glm::vec3(0.25f, 0.5f, 0.75f)); // flat: uv ignored
    const float grey = srgbToLinear(128.0f / 255.0f);
    // Texel centres: uv (0.25, 0.25) is the bottom-left texel, image row 1.
    expectNear(lookup.at(1, {0.25f, 0.25f}), glm::vec3(0, 0, 1));
    expectNear(lookup.at(1, {0.75f, 0.25f}), glm::vec3(grey));
    expectNear(lookup.at(1, {0.25f, 0.75f}), glm::vec3(1, 0, 0));
    expectNear(lookup.at(1, {0.75f, 0.75f}), glm::vec3(0, 1, 0));
    // Bilinear between centres, in linear space: the middle averages all four decoded texels.
    expectNear(lookup.at(1, {0.5f, 0.5f}), 0.25f * glm::vec3(1 + grey, 1 + grey, 1 + grey));
    // Repeat wrap: the left edge blends with the right column.
    expectNear(lookup.at(1, {1.25f, -0.75f}), glm::vec3(0, 0, 1));
    expectNear(lookup.at(1, {0.0f, 0.25f}), 0.5f * glm::vec3(grey, grey, 1 + grey));
}

TEST(AlbedoLookup, MaterialOutOfRangeIsAnError) {
    Scene s = texturedScene();
    AlbedoLookup lookup(s);
    EXPECT_THROW(lookup.at(2, {0.0f, 0.0f}), Error);
}
