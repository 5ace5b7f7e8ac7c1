#include "cli/OutputFiles.h"

#include "base/Error.h"
#include "base/Json.h"
#include "base/RunEnvironment.h"
#include "image/ImageIO.h"

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace bl::cli {

std::vector<std::string> writeRenderOutputs(const std::string& exrPath, const ImageSet& images, const Mode& mode,
                                            const RenderRecord& record) {
    fs::path exr(exrPath);
    if (exr.has_parent_path()) {
        fs::create_directories(exr.parent_path());
    }
    const RunEnvironment env = currentRunEnvironment();
    std::map<std::string, std::string> attributes = {
        {"bundlelab/scene", record.scene},   {"bundlelab/mode", std::string(mode.name())},
        {"bundlelab/device", record.device}, {"bundlelab/revision", env.gitRevision},
        {"bundlelab/iterations", std::to_string(images.iterations)}};
    for (const auto& [k, v] : mode.settings().resolved()) {
        attributes["bundlelab/settings/" + k] = v;
    }
    std::vector<ImageLayer> layers;
    for (const auto& [name, image] : images.layers) {
        layers.push_back({name, &image});
    }
    writeExr(exr.string(), layers, attributes);

    fs::path png = fs::path(exr).replace_extension(".png");
    writePng(png.string(), images.radiance());

    fs::path json = fs::path(exr).replace_extension(".json");
    std::string tmp = json.string() + ".tmp";
    {
        std::ofstream out(tmp);
        JsonWriter w(out);
        w.beginObject();
        w.field("scene", record.scene).field("mode", std::string(mode.name()));
        w.field("image", exr.filename().string()).field("preview", png.filename().string());
        w.field("width", images.radiance().width()).field("height", images.radiance().height());
        w.field("iterations", images.iterations).field("seed", static_cast<unsigned long long>(record.seed));
        w.field("wall_seconds", record.wallSeconds).field("setup_seconds", record.setupSeconds);
        w.field("partial", record.partial).field("frame", record.frame).field("scene_time", record.sceneTime);
        w.field("non_finite_samples", static_cast<unsigned long long>(images.nonFiniteSamples));
        const double samples = double(images.radiance().pixelCount()) * images.iterations;
        w.field("samples_per_second", record.wallSeconds > 0.0 ? samples / record.wallSeconds : 0.0);
        w.key("counters").beginObject();
        for (const auto& [name, value] : images.counters) {
            w.field(name, value);
            w.field(name + "_per_second", record.wallSeconds > 0.0 ? value / record.wallSeconds : 0.0);
        }
        w.endObject();
        w.key("settings").beginObject();
        for (const auto& [k, v] : mode.settings().resolved()) {
            w.field(k, v);
        }
        w.endObject();
        w.key("passes").beginArray();
        for (const PassTime& p : mode.timings()) {
            w.beginObject().field("name", p.name).field("total_ms", p.totalMs).field("count", p.count);
            w.field("mean_ms", p.meanMs()).endObject();
        }
        w.endArray();
        w.key("environment").beginObject();
        w.field("device", record.device).field("cpu", env.cpu).field("hardware_threads", env.hardwareThreads);
        w.field("build_type", env.buildType).field("git_revision", env.gitRevision).field("version", env.version);
        w.endObject();
        w.endObject();
        out << "\n";
        if (!out) {
            throw Error(json.string() + ": cannot write");
        }
    }
    fs::rename(tmp, json);
    return {exr.string(), png.string(), json.string()};
}

} // namespace bl::cli
