#include "image/Metrics.h"

#include "base/Error.h"

#include <algorithm>
#include <cmath>

namespace bl {

namespace {
void requireSameSize(const Image& a, const Image& b) {
    if (a.width() != b.width() || a.height() != b.height()) {
        throw Error("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                    " against " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
    }
}
} // namespace

ImageMetrics computeMetrics(const Image& test, const Image& reference, const MetricOptions& o) {
    requireSameSize(test, reference);
    ImageMetrics m;
    const std::size_t n = test.pixelCount();
    if (n == 0) {
        return m;
    }
    double se = 0.0, rel = 0.0, smape = 0.0, ae = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3& t = test.pixels()[i];
        const glm::vec3& r = reference.pixels()[i];
        for (int c = 0; c < 3; ++c) {
            double d = double(t[c]) - double(r[c]);
            se += d * d;
            rel += d * d / (double(r[c]) * r[c] + o.relEpsilon);
            ae += std::abs(d);
            double denominator = std::abs(double(t[c])) + std::abs(double(r[c]));
            smape += denominator > 0.0 ? 2.0 * std::abs(d) / denominator : 0.0;
        }
    }
    const double count = 3.0 * double(n);
    m.mse = se / count;
    m.rmse = std::sqrt(m.mse);
    m.relMse = rel / count;
    m.smape = smape / count;
    m.mae = ae / count;
    m.meanTest = test.mean();
    m.meanReference = reference.mean();
    for (int c = 0; c < 3; ++c) {
        m.meanRatio[c] = m.meanReference[c] != 0.0 ? m.meanTest[c] / m.meanReference[c] : 0.0;
    }

    const int b = std::max(o.blockSize, 1);
    const double floor = o.blockFloor * (m.meanReference.x + m.meanReference.y + m.meanReference.z);
    double sum = 0.0, sumSq = 0.0;
    for (int by = 0; by + b <= test.height(); by += b) {
        for (int bx = 0; bx + b <= test.width(); bx += b) {
            double st = 0.0, sr = 0.0;
            for (int y = by; y < by + b; ++y) {
                for (int x = bx; x < bx + b; ++x) {
                    const glm::vec3& t = test.at(x, y);
                    const glm::vec3& r = reference.at(x, y);
                    st += double(t.x) + t.y + t.z;
                    sr += double(r.x) + r.y + r.z;
                }
            }
            if (sr / (b * b) <= floor) {
                continue;
            }
            double ratio = st / sr;
            sum += ratio;
            sumSq += (ratio - 1.0) * (ratio - 1.0);
            m.blockRatios.maxDeviation = std::max(m.blockRatios.maxDeviation, std::abs(ratio - 1.0));
            ++m.blockRatios.blocks;
        }
    }
    if (m.blockRatios.blocks) {
        m.blockRatios.mean = sum / double(m.blockRatios.blocks);
        m.blockRatios.rms = std::sqrt(sumSq / double(m.blockRatios.blocks));
    }
    return m;
}

Image boxDownsample(const Image& image, int factor) {
    if (factor < 1 || image.width() % factor != 0 || image.height() % factor != 0) {
        throw Error("cannot box-downsample " + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                    " by " + std::to_string(factor));
    }
    Image out(image.width() / factor, image.height() / factor);
    const float scale = 1.0f / float(factor * factor);
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            glm::dvec3 s(0.0);
            for (int j = 0; j < factor; ++j)
                for (int i = 0; i < factor; ++i) s += glm::dvec3(image.at(x * factor + i, y * factor + j));
            out.at(x, y) = glm::vec3(s) * scale;
        }
    }
    return out;
}

void matchResolution(Image& a, Image& b) {
    if (a.width() == b.width() && a.height() == b.height()) {
        return;
    }
    Image& big = a.width() > b.width() ? a : b;
    const Image& small = a.width() > b.width() ? b : a;
    if (small.width() == 0 || big.width() % small.width() != 0 ||
        big.width() / small.width() * small.height() != big.height()) {
        throw Error("images of " + std::to_string(a.width()) + "x" + std::to_string(a.height()) + " and " +
                    std::to_string(b.width()) + "x" + std::to_string(b.height()) +
                    " differ by no integer factor");
    }
    big = boxDownsample(big, big.width() / small.width());
}

std::vector<float> errorValues(const Image& test, const Image& reference, const std::string& kind, double relEpsilon) {
    requireSameSize(test, reference);
    std::vector<float> out(test.pixelCount());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::vec3& t = test.pixels()[i];
        const glm::vec3& r = reference.pixels()[i];
        if (kind == "abs") {
            out[i] = std::abs(t.x - r.x) + std::abs(t.y - r.y) + std::abs(t.z - r.z);
        } else if (kind == "relmse") {
            double s = 0.0;
            for (int c = 0; c < 3; ++c) s += double(t[c] - r[c]) * (t[c] - r[c]) / (double(r[c]) * r[c] + relEpsilon);
            out[i] = float(s / 3.0);
        } else if (kind == "ratio") {
            double st = double(t.x) + t.y + t.z, sr = double(r.x) + r.y + r.z;
            out[i] = (st > 0.0 && sr > 0.0) ? float(std::log2(st / sr)) : 0.0f;
        } else {
            throw Error("unknown error map '" + kind + "' (abs, relmse, ratio)");
        }
    }
    return out;
}

namespace {
// A perceptually ordered dark-blue -> green -> yellow ramp (after matplotlib's viridis), in sRGB.
glm::vec3 sequential(float t) {
    static const glm::vec3 stops[] = {{0.267f, 0.005f, 0.329f}, {0.229f, 0.322f, 0.546f}, {0.128f, 0.567f, 0.551f},
                                      {0.369f, 0.789f, 0.383f}, {0.993f, 0.906f, 0.144f}};
    t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
    int i = std::min(static_cast<int>(t), 3);
    return glm::mix(stops[i], stops[i + 1], t - float(i));
}

glm::vec3 diverging(float t) { // t in [-1, 1]: blue, white, red (sRGB)
    t = std::clamp(t, -1.0f, 1.0f);
    return t < 0.0f ? glm::mix(glm::vec3(1.0f), glm::vec3(0.23f, 0.30f, 0.75f), -t)
                    : glm::mix(glm::vec3(1.0f), glm::vec3(0.71f, 0.02f, 0.15f), t);
}
} // namespace

Image falseColour(const std::vector<float>& values, int width, int height, bool signedValues, float maxValue) {
    if (maxValue <= 0.0f) {
        std::vector<float> mags;
        for (float v : values) mags.push_back(std::abs(v));
        if (!mags.empty()) {
            auto k = mags.begin() + static_cast<std::ptrdiff_t>(0.99 * (mags.size() - 1));
            std::nth_element(mags.begin(), k, mags.end());
            maxValue = *k;
        }
        if (!(maxValue > 0.0f)) maxValue = 1.0f;
    }
    Image out(width, height);
    for (std::size_t i = 0; i < values.size(); ++i) {
        glm::vec3 srgb = signedValues ? diverging(values[i] / maxValue) : sequential(values[i] / maxValue);
        // Images hold linear values; the PNG writer encodes sRGB again.
        out.pixels()[i] = glm::vec3(srgbToLinear(srgb.x), srgbToLinear(srgb.y), srgbToLinear(srgb.z));
    }
    return out;
}

} // namespace bl
