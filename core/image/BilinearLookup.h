// Bilinear filtering between texel centres, as a GPU sampler does (row 0 at the top).
#pragma once

#include "image/Image.h"

#include <algorithm>
#include <cmath>

namespace bl {

enum class Wrap { Repeat, Clamp };

// (u, v) in texture space: u = 0 left edge, v = 0 top edge. Non-finite coordinates read texel 0.
inline glm::vec3 bilinearLookup(const Image& img, glm::vec2 uv, Wrap wrapU, Wrap wrapV) {
    const int w = img.width(), h = img.height();
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
        return img.at(0, 0);
    }
    // Reduce to [0, 1] first so huge coordinates never overflow an int.
    auto reduce = [](float t, Wrap mode) { return mode == Wrap::Repeat ? t - std::floor(t) : std::clamp(t, 0.0f, 1.0f); };
    float fx = reduce(uv.x, wrapU) * w - 0.5f, fy = reduce(uv.y, wrapV) * h - 0.5f;
    float x0f = std::floor(fx), y0f = std::floor(fy);
    float tx = fx - x0f, ty = fy - y0f;
    int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    auto index = [](int i, int n, Wrap mode) { return mode == Wrap::Repeat ? (i + n) % n : std::clamp(i, 0, n - 1); };
    auto texel = [&](int x, int y) { return img.at(index(x, w, wrapU), index(y, h, wrapV)); };
    glm::vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), tx);
    glm::vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), tx);
    return glm::mix(top, bottom, ty);
}

} // namespace bl
