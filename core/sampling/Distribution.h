// Piecewise-constant 1D and 2D distributions for importance sampling (light selection, emissive
// triangles, environment maps). Sums in double so millions of tiny weights stay exact enough.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace bl {

class Distribution1D {
public:
    Distribution1D() = default;
    // Weights must be finite and non-negative; all zero makes an empty distribution.
    explicit Distribution1D(const std::vector<float>& weights);

    bool empty() const { return mTotal <= 0.0; }
    std::size_t size() const { return mPdf.size(); }
    double total() const { return mTotal; }
    // Discrete: index with probability weight / total.
    std::size_t sampleDiscrete(float u, float* probability = nullptr, float* remapped = nullptr) const;
    float probability(std::size_t i) const { return mPdf[i]; }
    // Continuous on [0, 1): piecewise-constant density (size() * probability of the segment).
    float sampleContinuous(float u, float* density = nullptr, std::size_t* index = nullptr) const;

private:
    std::vector<double> mCdf; // size() + 1 entries, mCdf.back() == 1
    std::vector<float> mPdf;  // discrete probabilities
    double mTotal = 0.0;
};

// Over [0,1)^2 with weights[y * width + x]: a marginal over rows, then a conditional per row.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(const std::vector<float>& weights, int width, int height);

    bool empty() const { return mMarginal.empty(); }
    // (u, v) in [0,1)^2 with the density returned in *density (with respect to du dv).
    glm::vec2 sample(glm::vec2 u, float* density) const;
    float density(glm::vec2 uv) const;

private:
    int mWidth = 0;
    int mHeight = 0;
    std::vector<Distribution1D> mRows;
    Distribution1D mMarginal;
};

} // namespace bl
