// Image error metrics against a reference. All sums in double; channels pooled unless noted.
//   mse     mean (t - r)^2                          rmse  sqrt(mse)
//   relmse  mean (t - r)^2 / (r^2 + epsilon)        (epsilon = 0.01 by default, as is customary)
//   smape   mean 2 |t - r| / (|t| + |r|)            (terms with t = r = 0 count as 0)
//   mae     mean |t - r|
//   mean ratio (per channel): mean(t) / mean(r)
//   block ratios: for each blockSize^2 block, mean(t) / mean(r) over the block's channel sums;
//   their spread sees bias through noise that per-pixel metrics drown in. Blocks whose reference
//   mean is below `blockFloor` times the image mean are skipped (ratios of nothing).
#pragma once

#include "image/Image.h"

#include <string>
#include <vector>

namespace bl {

struct MetricOptions {
    double relEpsilon = 0.01;
    int blockSize = 8;
    double blockFloor = 1e-3;
};

struct BlockRatioStats {
    std::size_t blocks = 0;
    double mean = 0.0; // mean ratio
    double rms = 0.0;  // RMS of (ratio - 1)
    double maxDeviation = 0.0;
};

struct ImageMetrics {
    double mse = 0.0;
    double rmse = 0.0;
    double relMse = 0.0;
    double smape = 0.0;
    double mae = 0.0;
    glm::dvec3 meanTest{0.0};
    glm::dvec3 meanReference{0.0};
    glm::dvec3 meanRatio{0.0};
    BlockRatioStats blockRatios;
};

// Throws bl::Error if the sizes differ.
ImageMetrics computeMetrics(const Image& test, const Image& reference, const MetricOptions& options = {});

// Averages factor x factor blocks (the box filter). Throws unless the size divides evenly.
Image boxDownsample(const Image& image, int factor);
// Brings two images to the same size by box-downsampling the larger by an integer factor.
void matchResolution(Image& a, Image& b);

// Per-pixel error images ("abs": |t - r| summed over channels; "relmse": (t - r)^2 / (r^2 + eps)
// averaged over channels; "ratio": log2 of the channel-sum ratio, signed) and a false-colour
// rendering of one: a perceptual sequential map for unsigned errors (0 .. maxValue), a diverging
// blue-white-red map for signed ones (-maxValue .. maxValue). maxValue <= 0 picks the 99th percentile.
std::vector<float> errorValues(const Image& test, const Image& reference, const std::string& kind,
                               double relEpsilon = 0.01);
Image falseColour(const std::vector<float>& values, int width, int height, bool signedValues, float maxValue);

} // namespace bl
