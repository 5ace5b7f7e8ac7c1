// What the mode tests that hold seeds' image means to a reference share (atlas, skylight): the
// reflected light of an image set, the luminance mean of an image, and the harness's check of the
// seeds' means against an expected value, printed the same way everywhere.
#pragma once

#include "modes/Mode.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "support/Statistics.h"

#include <cstdio>
#include <string>
#include <vector>

namespace bl::test {

// The light an image set shows reflected: radiance less the emitted layer (emitters and the
// background seen directly, which a view samples rather than estimates).
inline Image reflectedLight(const ImageSet& set) {
    Image light = set.radiance();
    const Image& emitted = layerOf(set, "emitted");
    for (std::size_t p = 0; p < light.pixelCount(); ++p) light.pixels()[p] -= emitted.pixels()[p];
    return light;
}

// The luminance image mean of an image.
inline double lumaMean(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += stats::luminance(p);
    return sum / double(image.pixelCount());
}

// The seeds' means against `expected` within `tolerance` (absolute), printed.
inline void expectSeedsAgree(const std::vector<double>& perSeed, double expected, double tolerance,
                             const std::string& what) {
    const stats::Summary s = stats::summarize(perSeed);
    std::printf("%s: %.6g +- %.3g (stderr; seeds' sd %.3g, %zu seeds), expected %.6g (%+.3f%%), tolerance %.3g "
                "(%.3f%%)\n",
                what.c_str(), s.mean, s.stderr_, s.stddev, s.n, expected, 100.0 * (s.mean / expected - 1.0), tolerance,
                100.0 * tolerance / expected);
    EXPECT_TRUE(stats::agrees(s, expected, tolerance, what));
}

} // namespace bl::test
