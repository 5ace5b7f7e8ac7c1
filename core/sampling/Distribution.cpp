#include "sampling/Distribution.h"

#include "base/Error.h"

#include <algorithm>
#include <cmath>

namespace bl {

Distribution1D::Distribution1D(const std::vector<float>& weights) : mPdf(weights.size(), 0.0f) {
    mCdf.assign(weights.size() + 1, 0.0);
    for (std::size_t i = 0; i < weights.size(); ++i) {
        if (!(weights[i] >= 0.0f) || !std::isfinite(weights[i])) {
            throw Error("Distribution1D: weight " + std::to_string(i) + " is negative or not finite");
        }
        mCdf[i + 1] = mCdf[i] + weights[i];
    }
    mTotal = mCdf.back();
    if (mTotal > 0.0) {
        for (std::size_t i = 0; i < weights.size(); ++i) {
            mPdf[i] = static_cast<float>(weights[i] / mTotal);
            mCdf[i + 1] /= mTotal;
        }
        mCdf.back() = 1.0;
    }
}

std::size_t Distribution1D::sampleDiscrete(float u, float* probability, float* remapped) const {
    // The last segment with cdf <= u; segments of zero weight are never chosen.
    auto it = std::upper_bound(mCdf.begin(), mCdf.end(), static_cast<double>(u));
    std::size_t i = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - mCdf.begin() - 1, 0), mPdf.size() - 1);
    while (mPdf[i] == 0.0f && i > 0) {
        --i;
    }
    if (probability) {
        *probability = mPdf[i];
    }
    if (remapped) {
        double width = mCdf[i + 1] - mCdf[i];
        *remapped = width > 0.0 ? std::clamp(static_cast<float>((u - mCdf[i]) / width), 0.0f, 0.99999994f) : 0.0f;
    }
    return i;
}

float Distribution1D::sampleContinuous(float u, float* density, std::size_t* index) const {
    float p = 0.0f, offset = 0.0f;
    std::size_t i = sampleDiscrete(u, &p, &offset);
    if (density) {
        *density = p * static_cast<float>(mPdf.size());
    }
    if (index) {
        *index = i;
    }
    return (static_cast<float>(i) + offset) / static_cast<float>(mPdf.size());
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : mWidth(width), mHeight(height) {
    std::vector<float> rowSums(height);
    for (int y = 0; y < height; ++y) {
        std::vector<float> row(weights.begin() + static_cast<std::ptrdiff_t>(y) * width,
                               weights.begin() + static_cast<std::ptrdiff_t>(y + 1) * width);
        mRows.emplace_back(row);
        rowSums[y] = static_cast<float>(mRows.back().total());
    }
    mMarginal = Distribution1D(rowSums);
    if (mMarginal.empty()) {
        mRows.clear();
    }
}

glm::vec2 Distribution2D::sample(glm::vec2 u, float* density) const {
    float dv = 0.0f, du = 0.0f;
    std::size_t row = 0;
    float v = mMarginal.sampleContinuous(u.y, &dv, &row);
    float x = mRows[row].sampleContinuous(u.x, &du);
    *density = du * dv;
    return {x, v};
}

float Distribution2D::density(glm::vec2 uv) const {
    if (empty()) {
        return 0.0f;
    }
    int x = std::clamp(static_cast<int>(uv.x * mWidth), 0, mWidth - 1);
    int y = std::clamp(static_cast<int>(uv.y * mHeight), 0, mHeight - 1);
    return mMarginal.probability(y) * mHeight * mRows[y].probability(x) * mWidth;
}

} // namespace bl
