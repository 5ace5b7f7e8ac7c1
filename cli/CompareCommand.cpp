// bundlelab compare TEST.exr REFERENCE.exr [--metric M ...] [--heatmap out.png] [--json]
#include "base/Error.h"
#include "base/Json.h"
#include "cli/Commands.h"
#include "cli/FiniteRange.h"
#include "image/ImageIO.h"
#include "image/Metrics.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace bl::cli {

namespace {

struct CompareOptions {
    std::string test;
    std::string reference;
    std::string layer;
    std::vector<std::string> metrics;
    std::string heatmap;
    std::string heatmapKind = "relmse";
    float heatmapMax = 0.0f;
    bool json = false;
    MetricOptions metricOptions;
};

const std::vector<std::string> kMetricNames = {"mse",      "rmse",       "relmse",          "smape",
                                               "mae",      "mean_ratio", "block_ratio_rms", "block_ratio_mean",
                                               "block_ratio_max"};

int runCompare(const CompareOptions& o) {
    Image test = readImage(o.test, o.layer);
    Image reference = readImage(o.reference, o.layer);
    matchResolution(test, reference);
    ImageMetrics m = computeMetrics(test, reference, o.metricOptions);
    std::vector<std::string> wanted = o.metrics.empty() ? kMetricNames : o.metrics;
    for (const std::string& name : wanted) {
        if (std::find(kMetricNames.begin(), kMetricNames.end(), name) == kMetricNames.end()) {
            throw Error("unknown metric '" + name + "'");
        }
    }
    auto scalar = [&](const std::string& name) -> double {
        if (name == "mse") return m.mse;
        if (name == "rmse") return m.rmse;
        if (name == "relmse") return m.relMse;
        if (name == "smape") return m.smape;
        if (name == "mae") return m.mae;
        if (name == "block_ratio_rms") return m.blockRatios.rms;
        if (name == "block_ratio_mean") return m.blockRatios.mean;
        return m.blockRatios.maxDeviation;
    };
    if (o.json) {
        JsonWriter w(std::cout);
        w.beginObject().field("test", o.test).field("reference", o.reference);
        w.field("width", test.width()).field("height", test.height());
        w.field("relmse_epsilon", o.metricOptions.relEpsilon).field("block_size", o.metricOptions.blockSize);
        w.field("blocks", static_cast<unsigned long long>(m.blockRatios.blocks));
        for (const std::string& name : wanted) {
            if (name == "mean_ratio") {
                w.key(name).beginArray().value(m.meanRatio.x).value(m.meanRatio.y).value(m.meanRatio.z).endArray();
            } else {
                w.field(name, scalar(name));
            }
        }
        w.endObject();
        std::cout << "\n";
    } else {
        std::printf("%s vs %s (%dx%d)\n", o.test.c_str(), o.reference.c_str(), test.width(), test.height());
        for (const std::string& name : wanted) {
            if (name == "mean_ratio") {
                std::printf("  %-18s %.6f %.6f %.6f\n", name.c_str(), m.meanRatio.x, m.meanRatio.y, m.meanRatio.z);
            } else {
                std::printf("  %-18s %.6g\n", name.c_str(), scalar(name));
            }
        }
        std::printf("  (relmse epsilon %g; block ratios over %zu blocks of %dx%d)\n", o.metricOptions.relEpsilon,
                    m.blockRatios.blocks, o.metricOptions.blockSize, o.metricOptions.blockSize);
    }
    if (!o.heatmap.empty()) {
        std::vector<float> values = errorValues(test, reference, o.heatmapKind, o.metricOptions.relEpsilon);
        writePng(o.heatmap, falseColour(values, test.width(), test.height(), o.heatmapKind == "ratio", o.heatmapMax));
        if (!o.json) std::printf("wrote %s\n", o.heatmap.c_str());
    }
    return 0;
}

} // namespace

void addCompareCommand(CLI::App& app, Action& action) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand("compare", "error metrics of an image against a reference");
    cmd->add_option("test", o->test, "image to judge (EXR, HDR or PNG)")->required();
    cmd->add_option("reference", o->reference, "reference image; sizes may differ by an integer factor")->required();
    cmd->add_option("--metric", o->metrics, "metrics to print (default all): mse rmse relmse smape mae mean_ratio "
                                            "block_ratio_rms block_ratio_mean block_ratio_max");
    cmd->add_option("--layer", o->layer, "EXR layer to compare (default: the main RGB)");
    cmd->add_option("--epsilon", o->metricOptions.relEpsilon, "epsilon of relMSE")->check(finiteRange(0.0, 1e30));
    cmd->add_option("--block", o->metricOptions.blockSize, "block size of the block-mean ratios")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--heatmap", o->heatmap, "write a false-colour error map (PNG)");
    cmd->add_option("--heatmap-kind", o->heatmapKind, "abs, relmse or ratio (signed log2)")
        ->check(CLI::IsMember({"abs", "relmse", "ratio"}));
    cmd->add_option("--heatmap-max", o->heatmapMax, "value at the top of the colour scale (default: 99th percentile)");
    cmd->add_flag("--json", o->json, "print JSON");
    cmd->callback([o, &action] { action = [o] { return runCompare(*o); }; });
}

} // namespace bl::cli
