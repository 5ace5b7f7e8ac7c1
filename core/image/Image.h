// Linear RGB float image, row 0 at the top.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace bl {

class Image {
public:
    Image() = default;
    Image(int width, int height, glm::vec3 fill = glm::vec3(0.0f));

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    std::size_t pixelCount() const { return mPixels.size(); }
    bool empty() const { return mPixels.empty(); }

    glm::vec3& at(int x, int y) { return mPixels[static_cast<std::size_t>(y) * mWidth + x]; }
    const glm::vec3& at(int x, int y) const {
        return mPixels[static_cast<std::size_t>(y) * mWidth + x];
    }
    std::vector<glm::vec3>& pixels() { return mPixels; }
    const std::vector<glm::vec3>& pixels() const { return mPixels; }

    // Mean over all pixels, accumulated in double.
    glm::dvec3 mean() const;
    // Number of pixels with a NaN or infinite channel.
    std::size_t countNonFinite() const;

private:
    int mWidth = 0;
    int mHeight = 0;
    std::vector<glm::vec3> mPixels;
};

// An 8-bit RGBA texture as stored on disk (sRGB-encoded colour), for upload to the GPU.
struct Rgba8Image {
    int width = 0;
    int height = 0;
    std::vector<unsigned char> texels; // width * height * 4, row 0 at the top
};

// Exact sRGB transfer functions (IEC 61966-2-1).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

} // namespace bl
