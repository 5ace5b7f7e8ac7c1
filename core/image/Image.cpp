#include "image/Image.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bl {

Image::Image(int width, int height, glm::vec3 fill) : mWidth(width), mHeight(height) {
    if (width < 0 || height < 0) {
        throw std::invalid_argument("Image: negative size " + std::to_string(width) + "x" +
                                    std::to_string(height));
    }
    mPixels.assign(static_cast<std::size_t>(width) * height, fill);
}

glm::dvec3 Image::mean() const {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& p : mPixels) {
        sum += glm::dvec3(p);
    }
    return mPixels.empty() ? sum : sum / static_cast<double>(mPixels.size());
}

std::size_t Image::countNonFinite() const {
    std::size_t n = 0;
    for (const glm::vec3& p : mPixels) {
        n += !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    }
    return n;
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

} // namespace bl
