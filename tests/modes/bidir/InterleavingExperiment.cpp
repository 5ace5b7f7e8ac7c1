// Measurements behind experiments/bidir-interleaving.md (not tests: disabled, run by
// experiments/bidir-interleaving.sh with --gtest_also_run_disabled_tests). Every error is in
// luminance against the reference path tracer's layer (max_segments = 3: indirect1 is complete).
//   Spatial: the point-lit Cornell box, interleave 1 / 2 / 4 with the blur off and on at equal
//   frames, seeds' mean and spread of the image-mean bias and NRMSE, per-pixel variance across
//   seeds, and the blur's own bias (paired: same seed, same samples, blur on minus off).
//   Temporal: the animated Cornell box (block moves, camera dollies) and the same with the camera
//   held at its first pose, one iterate() per frame as a real-time renderer would, per frame NRMSE
//   against a reference at that frame's time, and flicker (mean |L_f - L_{f-1}| over static pixels).
//   TemporalImageMean(Animated): the image mean of temporal = on against off and the reference.
#include "modes/Registry.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "sampling/PixelSamples.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

using namespace bl;

namespace {

double luminance(const glm::vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

std::vector<double> pixels(const Image& im) {
    std::vector<double> v;
    for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x) v.push_back(luminance(im.at(x, y)));
    return v;
}

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / double(v.size());
}

double spread(const std::vector<double>& v) { // sample standard deviation
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / double(v.size() - 1));
}

// sqrt(mean (t - r)^2) / mean(r)
double nrmse(const std::vector<double>& t, const std::vector<double>& r) {
    double e = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) e += (t[i] - r[i]) * (t[i] - r[i]);
    return std::sqrt(e / double(t.size())) / mean(r);
}

std::string outDir() {
    const char* d = std::getenv("BL_EXPERIMENT_OUT");
    return d ? d : ".";
}

int envInt(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v ? std::atoi(v) : fallback;
}

std::vector<double> referenceAt(const Scene& s, double time, std::uint32_t spp, const std::string& layer = "indirect1") {
    std::unique_ptr<Mode> mode = createMode("reference", {"max_segments=3"});
    mode->setScene(s, nullptr);
    for (std::uint32_t i = 0; i < spp; ++i) mode->iterate({i, 1000, time});
    return pixels(bl::test::layerOf(mode->resolve(), layer));
}

// Adds BL_EXTRA's comma-separated bidir settings (they come last, so they override).
void appendExtraSettings(std::vector<std::string>& settings) {
    const char* e = std::getenv("BL_EXTRA");
    const std::string x = e ? e : "";
    for (std::size_t p = 0; p < x.size();) {
        std::size_t q = x.find(',', p);
        if (q == std::string::npos) q = x.size();
        settings.push_back(x.substr(p, q - p));
        p = q + 1;
    }
}

class InterleavingExperiment : public bl::test::VulkanTest {};

const std::vector<std::string> kBidir = {"strategy=mis", "bounces=1", "pairs_per_frame=16", "bundle_resolution=128",
                                         "shadow_resolution=512", "vpl_shadow_resolution=128"};

} // namespace

TEST_F(InterleavingExperiment, DISABLED_Spatial) {
    const int side = envInt("BL_SIDE", 64), frames = envInt("BL_FRAMES", 16), seeds = envInt("BL_SEEDS", 6);
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    s.camera.resolution = {side, side};
    const std::vector<double> ref = referenceAt(s, 0.0, envInt("BL_REFERENCE_SPP", 1024));
    const double refMean = mean(ref);
    std::ofstream csv(outDir() + "/spatial.csv");
    csv << "config,seeds,frames,bias_percent,bias_spread_percent,nrmse,nrmse_spread,pixel_variance,blur_bias_percent,"
           "blur_bias_region_rms_percent,seconds\n";
    std::vector<std::vector<double>> unfiltered; // per seed, of the last "off" config
    for (const auto& [name, extra] :
         std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"interleave=1", {"interleave=1"}},
             {"interleave=2 blur off", {"interleave=2", "interleave_filter=off"}},
             {"interleave=2 blur on", {"interleave=2", "interleave_filter=on"}},
             {"interleave=4 blur off", {"interleave=4", "interleave_filter=off"}},
             {"interleave=4 blur on", {"interleave=4", "interleave_filter=on"}}}) {
        std::vector<std::vector<double>> runs;
        std::vector<double> biases, errors;
        const auto start = std::chrono::steady_clock::now();
        for (int seed = 1; seed <= seeds; ++seed) {
            std::vector<std::string> settings = kBidir;
            settings.insert(settings.end(), extra.begin(), extra.end());
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (int f = 0; f < frames; ++f) mode->iterate({std::uint32_t(f), std::uint64_t(seed), 0.0});
            runs.push_back(pixels(bl::test::layerOf(mode->resolve(), "indirect1")));
            biases.push_back(100.0 * (mean(runs.back()) / refMean - 1.0));
            errors.push_back(nrmse(runs.back(), ref));
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        double variance = 0.0;
        for (std::size_t i = 0; i < ref.size(); ++i) {
            std::vector<double> v;
            for (const auto& r : runs) v.push_back(r[i]);
            variance += spread(v) * spread(v) / double(ref.size());
        }
        // The blur's own bias: paired with the unfiltered runs of the same seeds (same samples).
        double blurBias = 0.0, regionRms = 0.0;
        const bool blurred = name.find("blur on") != std::string::npos;
        if (blurred) {
            std::vector<double> diff(ref.size(), 0.0);
            for (int k = 0; k < seeds; ++k)
                for (std::size_t i = 0; i < ref.size(); ++i) diff[i] += (runs[k][i] - unfiltered[k][i]) / seeds;
            blurBias = 100.0 * mean(diff) / refMean;
            const int block = 8, blocks = side / block;
            for (int by = 0; by < blocks; ++by) {
                for (int bx = 0; bx < blocks; ++bx) {
                    double d = 0.0, r = 0.0;
                    for (int y = by * block; y < (by + 1) * block; ++y)
                        for (int x = bx * block; x < (bx + 1) * block; ++x) d += diff[y * side + x], r += ref[y * side + x];
                    regionRms += (d / r) * (d / r) / double(blocks * blocks);
                }
            }
            regionRms = 100.0 * std::sqrt(regionRms);
        } else {
            unfiltered = runs;
        }
        std::printf("%-22s bias %+.2f +- %.2f%%  NRMSE %.4f +- %.4f  pixel variance %.3g", name.c_str(), mean(biases),
                    spread(biases) / std::sqrt(double(seeds)), mean(errors), spread(errors), variance);
        if (blurred) std::printf("  blur's bias %+.2f%% (8x8 regions RMS %.2f%%)", blurBias, regionRms);
        std::printf("  %.1f s\n", seconds);
        csv << name << "," << seeds << "," << frames << "," << mean(biases) << ","
            << spread(biases) / std::sqrt(double(seeds)) << "," << mean(errors) << "," << spread(errors) << ","
            << variance << "," << blurBias << "," << regionRms << "," << seconds << "\n";
    }
}

TEST_F(InterleavingExperiment, DISABLED_Temporal) {
    const int side = envInt("BL_SIDE", 48), frames = envInt("BL_FRAMES", 12), runsPerConfig = envInt("BL_SEEDS", 3);
    const double fps = envInt("BL_FPS", 6);
    const auto spp = static_cast<std::uint32_t>(envInt("BL_REFERENCE_SPP", 256));
    std::ofstream csv(outDir() + "/temporal.csv");
    csv << "scene,config,run,frame,time,nrmse,flicker_percent,reference_flicker_percent\n";
    for (const bool dolly : {false, true}) {
        Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-animated.toml"));
        s.camera.resolution = {side, side};
        if (!dolly) s.camera.keys.clear(); // held at its first pose; the block still moves
        const std::string sceneName = dolly ? "camera dolly" : "static camera";
        std::vector<std::vector<double>> refs;
        for (int f = 0; f < frames; ++f) refs.push_back(referenceAt(s, f / fps, spp));
        // Static pixels: the reference's indirect1 changes by less than 2% between any two frames'
        // 4x4 block means (the moving block, its surroundings and, with the dolly, most of the
        // image are excluded), judged on block means so the reference's own noise does not decide.
        std::vector<bool> still(refs[0].size(), true);
        const int b = 4;
        for (std::size_t i = 0; i < still.size(); ++i) {
            const int x = int(i) % side, y = int(i) / side, x0 = x / b * b, y0 = y / b * b;
            auto block = [&](const std::vector<double>& r) {
                double m = 0.0;
                for (int yy = y0; yy < y0 + b; ++yy)
                    for (int xx = x0; xx < x0 + b; ++xx) m += r[yy * side + xx] / (b * b);
                return m;
            };
            const double m0 = block(refs[0]);
            for (const auto& r : refs) still[i] = still[i] && m0 > 0.0 && std::abs(block(r) / m0 - 1.0) < 0.02;
        }
        double stillCount = 0.0, stillMean = 0.0;
        for (std::size_t i = 0; i < still.size(); ++i)
            if (still[i]) stillCount += 1.0, stillMean += refs[0][i];
        stillMean /= std::max(stillCount, 1.0);
        std::printf("%s: %.0f of %zu pixels static\n", sceneName.c_str(), stillCount, still.size());
        auto flicker = [&](const std::vector<double>& a, const std::vector<double>& p) {
            double d = 0.0;
            for (std::size_t i = 0; i < a.size(); ++i)
                if (still[i]) d += std::abs(a[i] - p[i]);
            return 100.0 * d / std::max(stillCount, 1.0) / stillMean;
        };
        for (const std::string config : {"fixed set", "fresh set", "temporal", "temporal 2s2=1e-2"}) {
            std::vector<double> nrmseAll, flickerAll, flickerLate;
            for (int run = 0; run < runsPerConfig; ++run) {
                std::vector<std::string> settings = kBidir;
                const bool temporal = config.rfind("temporal", 0) == 0;
                settings.insert(settings.end(), {"interleave=2", std::string("temporal=") + (temporal ? "on" : "off")});
                if (config == "temporal 2s2=1e-2") settings.push_back("temporal_depth_variance=1e-2");
                std::unique_ptr<Mode> mode = createMode("bidir", settings);
                std::vector<double> previous;
                for (int f = 0; f < frames; ++f) {
                    // As `render --frames`: setScene per frame, one iterate() each.
                    mode->setScene(s, &ctx());
                    const std::uint64_t seed = 1 + 97 * run + (config == "fresh set" ? f : 0);
                    IterationInfo info;
                    info.seed = seed;
                    info.time = f / fps;
                    info.previousTime = f > 0 ? (f - 1) / fps : info.time;
                    info.frame = std::uint32_t(f);
                    mode->iterate(info);
                    std::vector<double> image = pixels(bl::test::layerOf(mode->resolve(), "indirect1"));
                    const double e = nrmse(image, refs[f]);
                    const double fl = previous.empty() ? -1.0 : flicker(image, previous);
                    const double rf = f == 0 ? -1.0 : flicker(refs[f], refs[f - 1]);
                    csv << sceneName << "," << config << "," << run << "," << f << "," << f / fps << "," << e << ","
                        << fl << "," << rf << "\n";
                    nrmseAll.push_back(e);
                    if (f >= 4) flickerLate.push_back(fl); // after the four caches are filled
                    if (fl >= 0.0) flickerAll.push_back(fl);
                    previous = std::move(image);
                }
            }
            std::printf("%-14s %-10s NRMSE %.4f +- %.4f (frames 0-%d), flicker %.3f%% (frames 1-%d), %.3f%% (4-%d)\n",
                        sceneName.c_str(), config.c_str(), mean(nrmseAll), spread(nrmseAll), frames - 1,
                        mean(flickerAll), frames - 1, mean(flickerLate), frames - 1);
        }
        std::vector<double> refFlicker;
        for (int f = 1; f < frames; ++f) refFlicker.push_back(flicker(refs[f], refs[f - 1]));
        std::printf("%-14s reference flicker (its own noise at %u spp + the true change) %.3f%%\n", sceneName.c_str(), spp,
                    mean(refFlicker));
    }
}

// Image mean of temporal = on against off and the reference on a static view (the report's
// "temporal image mean" section): per seed, the same frames (BL_FRAMES, 4: the same four sample
// sets for both) with each setting; paired ratios, the mean over seeds with its standard error,
// per-pixel means over seeds (temporal-bias.csv) and the on - off difference summed over 4x4 blocks
// as a share of the reference's image total. BL_REF4=1 also renders the reference 6x finer and
// reads it at the 2x2 sub-pixel centres and at the progressive jitter's first points (the pixel
// positions each setting samples). BL_EXTRA: comma-separated bidir settings added last.
TEST_F(InterleavingExperiment, DISABLED_TemporalImageMean) {
    const int side = envInt("BL_SIDE", 32), frames = envInt("BL_FRAMES", 4), seeds = envInt("BL_SEEDS", 20);
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    const std::string layerName = std::getenv("BL_LAYER") ? std::getenv("BL_LAYER") : "indirect1";
    s.camera.resolution = {side, side};
    std::vector<std::string> base = {"strategy=vpl",          "bounces=1",         "pairs_per_frame=8",
                                     "interleave=2",          "vpl_source=traced", "fit=scene",
                                     "bundle_resolution=128", "shadow_resolution=256", "vpl_shadow_resolution=128"};
    appendExtraSettings(base);
    std::vector<double> on(side * side, 0.0), off(side * side, 0.0);
    std::vector<double> seedOn, seedOff;
    for (int seed = 1; seed <= seeds; ++seed) {
        for (const bool t : {false, true}) {
            auto settings = base;
            settings.push_back(std::string("temporal=") + (t ? "on" : "off"));
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            mode->setScene(s, &ctx());
            for (int f = 0; f < frames; ++f) mode->iterate({std::uint32_t(f), std::uint64_t(seed), 0.0});
            const auto px = pixels(bl::test::layerOf(mode->resolve(), layerName));
            for (int i = 0; i < side * side; ++i) (t ? on : off)[i] += px[i] / seeds;
            (t ? seedOn : seedOff).push_back(mean(px));
            int top = 0;
            for (int i = 0; i < side * side; ++i) if (px[i] > px[top]) top = i;
            std::printf("seed %d %s mean %.6f max %.4f at (%d, %d)\n", seed, t ? "on " : "off", mean(px), px[top],
                        top % side, top / side);
        }
    }
    const std::vector<double> ref = referenceAt(s, 0.0, envInt("BL_REFERENCE_SPP", 1024), layerName);
    std::printf("image mean: off %.6f on %.6f ref %.6f (on/off %.4f, on/ref %.4f)\n", mean(off), mean(on), mean(ref),
                mean(on) / mean(off), mean(on) / mean(ref));
    {
        std::vector<double> ratio, dOn, dOff;
        for (int k = 0; k < seeds; ++k) {
            ratio.push_back(seedOn[k] / seedOff[k]);
            dOn.push_back(seedOn[k] / mean(ref));
            dOff.push_back(seedOff[k] / mean(ref));
        }
        const double r = std::sqrt(double(seeds));
        std::printf("per seed: on/off %.4f +- %.4f, on/ref %.4f +- %.4f, off/ref %.4f +- %.4f (mean +- standard error)\n",
                    mean(ratio), spread(ratio) / r, mean(dOn), spread(dOn) / r, mean(dOff), spread(dOff) / r);
    }
    {
        // Without the two outer pixel rows and columns, which the box's front edges cut.
        double sOn = 0.0, sOff = 0.0, sRef = 0.0;
        for (int y = 2; y < side - 2; ++y)
            for (int x = 2; x < side - 2; ++x) sOn += on[y * side + x], sOff += off[y * side + x], sRef += ref[y * side + x];
        std::printf("interior: on/ref %.4f, off/ref %.4f, on/off %.4f\n", sOn / sRef, sOff / sRef, sOn / sOff);
    }
    if (envInt("BL_REF4", 0)) {
        Scene fine = s;
        fine.camera.resolution = {6 * side, 6 * side};
        const std::vector<double> r6 = referenceAt(fine, 0.0, envInt("BL_REFERENCE_SPP", 1024) / 4, layerName);
        std::vector<double> ref4(side * side, 0.0);
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x)
                for (int j : {1, 4})
                    for (int i : {1, 4}) ref4[y * side + x] += 0.25 * r6[(6 * y + j) * 6 * side + 6 * x + i];
        std::printf("reference at the 2x2 sub-pixel centres: %.6f (box %.6f: %.4f); on / it %.4f, off / it %.4f\n",
                    mean(ref4), mean(ref), mean(ref4) / mean(ref), mean(on) / mean(ref4), mean(off) / mean(ref4));
        // The progressive jitter's first points of each seed's shift (PixelSamples.h), nearest fine
        // pixel centre, averaged over the seeds the renders used.
        std::vector<double> refH(side * side, 0.0);
        const int fineSide = 6 * side;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x)
                for (int seed = 1; seed <= seeds; ++seed)
                    for (std::uint32_t k = 0; k < std::uint32_t(frames); ++k) {
                        const glm::vec2 p = pixelSamplePosition(k, true, std::uint64_t(seed));
                        const int fx = std::min(fineSide - 1, 6 * x + int(6.0f * p.x));
                        const int fy = std::min(fineSide - 1, 6 * y + int(6.0f * p.y));
                        refH[y * side + x] += r6[fy * fineSide + fx] / (frames * seeds);
                    }
        std::printf("reference at the first %d progressive jitter points: %.6f (box: %.4f); off / it %.4f\n", frames,
                    mean(refH), mean(refH) / mean(ref), mean(off) / mean(refH));
    }
    const double total = mean(ref) * side * side;
    for (int by = 0; by < side / 4; ++by) {
        for (int bx = 0; bx < side / 4; ++bx) {
            double d = 0.0, o = 0.0;
            for (int y = by * 4; y < by * 4 + 4; ++y)
                for (int x = bx * 4; x < bx * 4 + 4; ++x) d += on[y * side + x] - off[y * side + x], o += ref[y * side + x];
            std::printf(" %+6.2f", 100.0 * d / total);
        }
        std::printf("\n");
    }
    std::ofstream f(outDir() + "/temporal-bias.csv");
    f << "x,y,off,on,ref\n";
    for (int i = 0; i < side * side; ++i) f << i % side << "," << i / side << "," << off[i] << "," << on[i] << "," << ref[i] << "\n";
}

// The same on the animated Cornell box, one iterate() per frame as `render --frames`: per frame,
// the image mean of temporal on and off (the fixed set) against that frame's reference, over seeds
// (BL_STATIC_CAMERA=1: the camera held at its first pose).
TEST_F(InterleavingExperiment, DISABLED_TemporalImageMeanAnimated) {
    const int side = envInt("BL_SIDE", 32), frames = envInt("BL_FRAMES", 8), seeds = envInt("BL_SEEDS", 20);
    const double fps = envInt("BL_FPS", 6);
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell-animated.toml"));
    s.camera.resolution = {side, side};
    if (envInt("BL_STATIC_CAMERA", 0)) s.camera.keys.clear();
    std::vector<std::string> base = {"pairs_per_frame=8", "interleave=2", "vpl_source=traced", "fit=scene",
                                     "bundle_resolution=128", "shadow_resolution=256", "vpl_shadow_resolution=128"};
    appendExtraSettings(base);
    std::vector<double> refMeans;
    for (int f = 0; f < frames; ++f) refMeans.push_back(mean(referenceAt(s, f / fps, envInt("BL_REFERENCE_SPP", 256))));
    std::vector<std::vector<double>> on(frames), off(frames);
    for (int seed = 1; seed <= seeds; ++seed) {
        for (const bool t : {false, true}) {
            auto settings = base;
            settings.push_back(std::string("temporal=") + (t ? "on" : "off"));
            std::unique_ptr<Mode> mode = createMode("bidir", settings);
            for (int f = 0; f < frames; ++f) {
                mode->setScene(s, &ctx());
                IterationInfo info;
                info.seed = std::uint64_t(seed);
                info.time = f / fps;
                info.previousTime = f > 0 ? (f - 1) / fps : info.time;
                info.frame = std::uint32_t(f);
                mode->iterate(info);
                (t ? on : off)[f].push_back(mean(pixels(bl::test::layerOf(mode->resolve(), "indirect1"))) / refMeans[f]);
            }
        }
    }
    const double r = std::sqrt(double(seeds));
    std::vector<double> allOn, allOff;
    for (int f = 0; f < frames; ++f) {
        std::printf("frame %d: on/ref %.4f +- %.4f, off/ref %.4f +- %.4f\n", f, mean(on[f]), spread(on[f]) / r,
                    mean(off[f]), spread(off[f]) / r);
        if (f >= 4) {
            allOn.insert(allOn.end(), on[f].begin(), on[f].end());
            allOff.insert(allOff.end(), off[f].begin(), off[f].end());
        }
    }
    std::printf("frames 4-%d: on/ref %.4f, off/ref %.4f\n", frames - 1, mean(allOn), mean(allOff));
}
