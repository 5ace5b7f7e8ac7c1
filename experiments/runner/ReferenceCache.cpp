#include "runner/ReferenceCache.h"

#include "base/Error.h"
#include "base/Json.h"
#include "base/Log.h"
#include "image/ImageIO.h"
#include "modes/Registry.h"
#include "runner/FileUtil.h"
#include "scene/SceneLoader.h"

#include <filesystem>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace bl {

namespace {
constexpr double kRelEpsilon = 0.01;
// The reference's own seed: no task seed may reproduce its samples, or a `reference` task would
// be compared with (part of) itself.
constexpr std::uint64_t kReferenceSeed = 0x9e3779b97f4a7c15ull;

void noiseOf(const Image& mean, const Image& variance, double& mse, double& rel) {
    double a = 0.0, b = 0.0;
    for (std::size_t i = 0; i < mean.pixelCount(); ++i) {
        for (int c = 0; c < 3; ++c) {
            double v = variance.pixels()[i][c], m = mean.pixels()[i][c];
            a += v;
            b += v / (m * m + kRelEpsilon);
        }
    }
    const double n = 3.0 * double(std::max<std::size_t>(mean.pixelCount(), 1));
    mse = a / n;
    rel = b / n;
}
} // namespace

ReferenceCache::ReferenceCache(const ExperimentConfig& config, std::string outDir)
    : mConfig(&config), mOutDir(std::move(outDir)) {}

std::string ReferenceCache::key(const Task& task) const {
    std::string k = task.scene;
    for (const auto& [name, v] : task.referenceSettings) k += "|" + name + "=" + formatValue(v);
    return k;
}

void ReferenceCache::prepare(const std::vector<const Task*>& tasks) {
    if (!mConfig->reference.enabled) {
        return;
    }
    for (const Task* t : tasks) {
        std::string k = key(*t);
        if (!mImages.count(k)) {
            mImages[k] = make(mConfig->scene(t->scene), t->referenceSettings);
        }
    }
}

std::string ReferenceCache::cachePath(const SceneEntry& s,
                                      const std::vector<std::pair<std::string, ParamValue>>& settingsList) const {
    std::string identity = s.fingerprint + "|" + std::to_string(mConfig->reference.spp);
    for (const auto& [k, v] : settingsList) identity += "|" + k + "=" + formatValue(v);
    return (fs::path(mOutDir) / "references" / (s.name + "-" + hashText(identity) + ".exr")).string();
}

std::size_t ReferenceCache::toRender(const std::vector<const Task*>& tasks) const {
    if (!mConfig->reference.enabled) {
        return 0;
    }
    std::map<std::string, bool> missing;
    for (const Task* t : tasks) {
        const SceneEntry& s = mConfig->scene(t->scene);
        if (!s.referenceFile.empty()) continue;
        const std::string exr = cachePath(s, t->referenceSettings);
        missing[exr] = !fs::is_regular_file(exr) || !fs::is_regular_file(fs::path(exr).replace_extension(".json"));
    }
    std::size_t n = 0;
    for (const auto& [path, m] : missing) n += m ? 1 : 0;
    return n;
}

ReferenceImage ReferenceCache::make(const SceneEntry& s,
                                    const std::vector<std::pair<std::string, ParamValue>>& settingsList) const {
    ReferenceImage ref;
    if (!s.referenceFile.empty()) {
        ref.image = readImage(s.referenceFile);
        ref.path = s.referenceFile;
        return ref;
    }
    const std::string exr = cachePath(s, settingsList);
    const std::string json = fs::path(exr).replace_extension(".json").string();
    if (!fs::is_regular_file(exr) || !fs::is_regular_file(json)) {
        log::info("reference for scene '" + s.name + "': rendering " + std::to_string(mConfig->reference.spp) +
                  " spp (cached as " + exr + ")");
        Scene scene = loadScene(s.file);
        if (s.resolution) scene.camera.resolution = *s.resolution;
        Settings settings(findMode("reference").parameters());
        for (const auto& [k, v] : settingsList) settings.set(k, v);
        std::unique_ptr<Mode> mode = findMode("reference").create(settings);
        mode->setScene(scene, nullptr);
        for (std::uint32_t i = 0; i < mConfig->reference.spp; ++i) {
            mode->iterate({i, kReferenceSeed, 0.0});
        }
        ImageSet out = mode->resolve();
        const Image* variance = nullptr;
        for (const auto& [name, image] : out.layers) {
            if (name == "variance") variance = &image;
        }
        double mse = 0.0, rel = 0.0;
        if (variance) noiseOf(out.radiance(), *variance, mse, rel);
        fs::create_directories(fs::path(exr).parent_path());
        writeExr(exr, out.radiance());
        writePng(fs::path(exr).replace_extension(".png").string(), out.radiance());
        writePfm(fs::path(exr).replace_extension(".pfm").string(), out.radiance());
        std::ostringstream j;
        JsonWriter w(j);
        w.beginObject().field("scene", s.name).field("spp", mConfig->reference.spp).field("noise_mse", mse);
        w.field("noise_relmse", rel);
        w.key("settings").beginObject();
        for (const auto& [k, v] : settings.resolved()) w.field(k, v);
        w.endObject().endObject();
        writeFileAtomic(json, j.str() + "\n");
    } else {
        log::info("reference for scene '" + s.name + "': cached " + exr);
    }
    ref.image = readImage(exr);
    ref.path = exr;
    ref.rendered = true;
    std::string text;
    readFileIfExists(json, text);
    auto number = [&](const std::string& k) {
        auto pos = text.find("\"" + k + "\": ");
        return pos == std::string::npos ? 0.0 : std::stod(text.substr(pos + k.size() + 4));
    };
    ref.noiseMse = number("noise_mse");
    ref.noiseRelMse = number("noise_relmse");
    return ref;
}

const ReferenceImage* ReferenceCache::find(const Task& task) const {
    auto it = mImages.find(key(task));
    return it == mImages.end() ? nullptr : &it->second;
}

} // namespace bl
