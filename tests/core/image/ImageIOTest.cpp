#include "image/ImageIO.h"
#include "support/TestFiles.h"

#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;
using bl::test::sharedPath;
using bl::test::tempDir;

TEST(Image, SrgbCurveIsExactAndInvertible) {
    EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.21404114f, 1e-7f);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-9f);
    for (float x = 0.0f; x <= 1.0f; x += 0.01f) {
        EXPECT_NEAR(linearToSrgb(srgbToLinear(x)), x, 1e-5f);
    }
}

TEST(ImageIO, ExrRoundTripWithLayersAndAttributes) {
    Image a(7, 5), b(7, 5);
    for (int y = 0; y < 5; ++y) {
        for (int x = 0; x < 7; ++x) {
            a.at(x, y) = glm::vec3(x, y, 1e-8f * x + 1e6f * y);
            b.at(x, y) = glm::vec3(-1.0f, 0.5f, float(x * y));
        }
    }
    std::string path = tempDir() + "/r.exr";
    writeExr(path, {{"", &a}, {"albedo", &b}}, {{"bundlelab/mode", "raster"}});
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    Image ra = readImage(path), rb = readImage(path, "albedo");
    EXPECT_EQ(ra.pixels(), a.pixels()); // float32: bit-exact
    EXPECT_EQ(rb.pixels(), b.pixels());
    EXPECT_EQ(exrLayers(path), (std::vector<std::string>{"", "albedo"}));
    EXPECT_NE(errorOf([&] { readImage(path, "normal"); }).find("no channel 'normal.R'"), std::string::npos);
}

TEST(ImageIO, PngPreviewAndErrors) {
    Image a(4, 4, glm::vec3(0.5f));
    a.at(0, 0) = glm::vec3(NAN);
    std::string path = tempDir() + "/p.png";
    writePng(path, a);
    Image back = readImage(path);
    EXPECT_NEAR(back.at(1, 1).x, 0.5f, 0.005f); // sRGB encode/decode at 8 bits
    EXPECT_EQ(back.at(0, 0), glm::vec3(1.0f, 0.0f, 1.0f)); // NaN shows as magenta
    EXPECT_NE(errorOf([] { readImage("/no/file.exr"); }).find("/no/file.exr: file not found"), std::string::npos);
    std::string junk = bl::test::writeTempFile("junk.exr", "not an exr");
    EXPECT_NE(errorOf([&] { readImage(junk); }).find("cannot read EXR"), std::string::npos);
}

TEST(ImageIO, ReadsTheSharedHdrAndReference) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    BL_SKIP_WITHOUT_SHARED("references/cornell-mcguire/mcguire-CornellBox-Original_256_1024spp.exr");
    Image sky = readImage(sharedPath("data/envmap/classroom-sky.hdr"));
    EXPECT_EQ(sky.width(), 512);
    EXPECT_GT(sky.mean().x, 0.0);
    Image ref = readImage(sharedPath("references/cornell-mcguire/mcguire-CornellBox-Original_256_1024spp.exr"));
    EXPECT_EQ(ref.width(), 256);
    // The README states the image mean.
    EXPECT_NEAR(ref.mean().x, 0.19457, 5e-5);
    EXPECT_NEAR(ref.mean().y, 0.12642, 5e-5);
    EXPECT_NEAR(ref.mean().z, 0.03569, 5e-5);
}
