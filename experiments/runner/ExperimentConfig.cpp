#include "runner/ExperimentConfig.h"

#include "base/Error.h"
#include "config/StrictToml.h"
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "scene/TextParsing.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

namespace fs = std::filesystem;

namespace bl {

namespace {

Budget readBudget(StrictTable& t, const Budget& fallback) {
    if (t.has("iterations") && t.has("seconds")) {
        t.fail("iterations", "give either iterations or seconds, not both");
    }
    Budget b = fallback;
    if (t.has("iterations")) {
        std::int64_t n = t.integer("iterations");
        if (n < 1 || n > (1 << 30)) t.fail("iterations", "value " + std::to_string(n) + " outside [1, 2^30]");
        b = {static_cast<std::uint32_t>(n), 0.0};
    } else if (t.has("seconds")) {
        double s = t.number("seconds");
        if (!(s > 0.0 && s <= 1e7)) t.fail("seconds", "value " + formatNumber(s) + " outside (0, 1e7]");
        b = {0, s};
    }
    return b;
}

std::string sanitize(const std::string& s) {
    std::string out;
    for (char c : s) {
        out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
    }
    return out;
}

std::string describe(const std::vector<std::pair<std::string, ParamValue>>& kv) {
    std::string s;
    for (const auto& [k, v] : kv) s += (s.empty() ? "" : ",") + k + "=" + formatValue(v);
    return s;
}

// An experiment's name is its output folder (results/<name>) and a scene's name is part of file
// names in it (references/<scene>-<hash>.exr): each must be one plain path component, so that no
// config can write outside the output directory.
std::string folderName(const StrictTable& t, const std::string& key, const std::string& name) {
    const bool control = std::any_of(name.begin(), name.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; });
    if (name.empty() || name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos || control ||
        name.size() > 200) {
        t.fail(key, "'" + name + "' is not a plain name (one folder or file name: no '/' or '\\', not '.' or '..', "
                    "no control characters, at most 200 characters); it names files in the output directory");
    }
    return name;
}

std::string resolvePath(const StrictTable& t, const std::string& name) {
    fs::path p = fs::path(name);
    return (p.is_absolute() ? p : fs::path(t.file()).parent_path() / p).lexically_normal().string();
}

} // namespace

std::string hashText(const std::string& text) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::vector<std::uint32_t> logCheckpoints(std::uint32_t iterations) {
    std::vector<std::uint32_t> c;
    for (std::uint32_t k = 1; k < iterations; k *= 2) c.push_back(k);
    c.push_back(iterations);
    return c;
}

const SceneEntry& ExperimentConfig::scene(const std::string& n) const {
    for (const SceneEntry& s : scenes) {
        if (s.name == n) return s;
    }
    throw Error("no scene named '" + n + "'");
}

ExperimentConfig loadExperimentConfig(const std::string& path) {
    TomlDocument doc(path);
    StrictTable root = doc.root();
    ExperimentConfig cfg;
    cfg.path = path;

    std::optional<StrictTable> exp = root.table("experiment");
    if (!exp) {
        throw Error(path + ": missing [experiment] table");
    }
    cfg.name = folderName(*exp, "name", exp->string("name"));
    auto integers = [&](StrictTable& t, const std::string& key, std::uint64_t lo, std::uint64_t hi) {
        std::vector<std::uint64_t> out;
        for (const ParamValue& v : t.list(key)) {
            const std::int64_t* i = std::get_if<std::int64_t>(&v);
            if (!i || *i < std::int64_t(lo) || std::uint64_t(*i) > hi) {
                t.fail(key, "expected integers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
            }
            out.push_back(static_cast<std::uint64_t>(*i));
        }
        return out;
    };
    if (exp->has("seeds")) {
        cfg.seeds = integers(*exp, "seeds", 0, 0xffffffffull);
        if (cfg.seeds.empty()) exp->fail("seeds", "empty");
    }
    cfg.budget = readBudget(*exp, Budget{64, 0.0});
    if (exp->isArray("checkpoints")) {
        cfg.logCheckpoints = false;
        for (std::uint64_t c : integers(*exp, "checkpoints", 1, 1u << 30)) {
            cfg.checkpoints.push_back(static_cast<std::uint32_t>(c));
        }
    } else if (exp->string("checkpoints", "log") != "log") {
        exp->fail("checkpoints", "expected \"log\" or an array of iterations");
    }
    constexpr std::int64_t kMaxFrames = 1 << 20;
    const std::int64_t frames = exp->integer("frames", 1);
    if (frames < 1 || frames > kMaxFrames) {
        exp->fail("frames", "value " + std::to_string(frames) + " outside [1, " + std::to_string(kMaxFrames) + "]");
    }
    cfg.frames.frames = static_cast<std::uint32_t>(frames);
    cfg.frames.frameRate = exp->number("frame_rate", kDefaultFrameRate);
    if (!(cfg.frames.frameRate > 0.0 && cfg.frames.frameRate <= 1e6)) {
        exp->fail("frame_rate", "value " + formatNumber(cfg.frames.frameRate) + " outside (0, 1e6] frames per second");
    }
    exp->finish();

    if (auto ref = root.table("reference")) {
        cfg.reference.enabled = ref->boolean("enabled", true);
        std::int64_t spp = ref->integer("spp", 256);
        if (spp < 1 || spp > (1 << 24)) ref->fail("spp", "value " + std::to_string(spp) + " outside [1, 2^24]");
        cfg.reference.spp = static_cast<std::uint32_t>(spp);
        for (const StrictTable::Entry& e : ref->entries("settings")) {
            if (e.isArray) throwAt(path, e.line, "reference.settings." + e.key + ": a single value expected");
            cfg.reference.settings.emplace_back(e.key, e.values[0]);
        }
        ref->finish();
        Settings check(findMode("reference").parameters());
        for (const auto& [k, v] : cfg.reference.settings) {
            try {
                check.set(k, v);
            } catch (const Error& err) {
                throwAt(path, ref->line("settings"), std::string("reference.settings: ") + err.what());
            }
        }
    }

    std::set<std::string> sceneNames;
    for (StrictTable& t : root.tables("scene")) {
        SceneEntry s;
        s.file = resolvePath(t, t.string("file"));
        s.name = folderName(t, "name", t.string("name", fs::path(s.file).stem().string()));
        if (!sceneNames.insert(s.name).second) t.fail("name", "duplicate scene name '" + s.name + "'");
        if (t.has("resolution")) {
            glm::ivec2 r = t.ivec2("resolution");
            if (r.x < 1 || r.y < 1 || r.x > kMaxResolution || r.y > kMaxResolution) {
                t.fail("resolution", "value outside [1, " + std::to_string(kMaxResolution) + "]");
            }
            s.resolution = r;
        }
        if (t.has("reference_file")) {
            s.referenceFile = resolvePath(t, t.string("reference_file"));
            if (!fs::is_regular_file(s.referenceFile)) t.fail("reference_file", "file not found: " + s.referenceFile);
        }
        t.finish();
        try {
            Scene loaded = loadScene(s.file); // every scene error before any task starts
            std::string identity = s.resolution ? std::to_string(s.resolution->x) + "x" + std::to_string(s.resolution->y) : "";
            for (const std::string& f : loaded.inputFiles) {
                // A file the loader looked for and did not find is part of the scene too (absent).
                identity += "|" + f + "|" + (fs::is_regular_file(f) ? hashText(readWholeFile(f)) : std::string("absent"));
            }
            s.fingerprint = hashText(identity);
        } catch (const Error& e) {
            throwAt(path, t.line("file"), std::string("scene '") + s.name + "': " + e.what());
        }
        cfg.scenes.push_back(s);
    }
    if (cfg.scenes.empty()) {
        throw Error(path + ": no [[scene]]");
    }

    std::uint32_t index = 0;
    std::vector<StrictTable> modes = root.tables("mode");
    if (modes.empty()) {
        throw Error(path + ": no [[mode]]");
    }
    std::set<std::string> labels;
    for (StrictTable& t : modes) {
        const std::string modeName = t.string("mode");
        const ModeEntry* entry = nullptr;
        try {
            entry = &findMode(modeName);
        } catch (const Error& e) {
            t.fail("mode", e.what());
        }
        const std::string label = t.string("label", modeName);
        if (!labels.insert(label).second) t.fail("label", "duplicate label '" + label + "' (give each [[mode]] a label)");
        Budget budget = readBudget(t, cfg.budget);
        std::vector<std::pair<std::string, ParamValue>> fixed;
        for (const StrictTable::Entry& e : t.entries("settings")) {
            if (e.isArray) throwAt(path, e.line, "settings." + e.key + ": a single value expected (use grid for lists)");
            fixed.emplace_back(e.key, e.values[0]);
        }
        std::vector<std::pair<std::string, ParamValue>> referenceSettings = cfg.reference.settings;
        for (const StrictTable::Entry& e : t.entries("reference")) {
            if (e.isArray) throwAt(path, e.line, "reference." + e.key + ": a single value expected");
            std::erase_if(referenceSettings, [&](const auto& kv) { return kv.first == e.key; });
            referenceSettings.emplace_back(e.key, e.values[0]);
            Settings check(findMode("reference").parameters());
            try {
                check.set(e.key, e.values[0]);
            } catch (const Error& err) {
                throwAt(path, e.line, std::string("mode '") + label + "' reference: " + err.what());
            }
        }
        std::vector<StrictTable::Entry> grid = t.entries("grid");
        std::set<std::string> only;
        for (const ParamValue& v : t.list("scenes")) {
            const std::string* name = std::get_if<std::string>(&v);
            if (!name || !sceneNames.count(*name)) {
                t.fail("scenes", "no [[scene]] named '" + formatValue(v) + "'");
            }
            only.insert(*name);
        }
        t.finish();

        // Cartesian product of the grid, in key order as written.
        std::vector<std::vector<std::pair<std::string, ParamValue>>> points{{}};
        for (const StrictTable::Entry& e : grid) {
            std::vector<std::vector<std::pair<std::string, ParamValue>>> next;
            for (const auto& p : points) {
                for (const ParamValue& v : e.values) {
                    auto q = p;
                    q.emplace_back(e.key, v);
                    next.push_back(q);
                }
            }
            points = next;
        }
        // Every grid point must be a valid setting of the mode.
        for (const auto& point : points) {
            Settings check(entry->parameters());
            for (const auto& [k, v] : fixed) {
                try {
                    check.set(k, v);
                } catch (const Error& e) {
                    throwAt(path, t.line("settings"), "mode '" + label + "' settings: " + e.what());
                }
            }
            for (const auto& [k, v] : point) {
                try {
                    check.set(k, v);
                } catch (const Error& e) {
                    throwAt(path, t.line("grid"), "mode '" + label + "' grid: " + e.what());
                }
            }
        }
        for (const SceneEntry& scene : cfg.scenes) {
            if (!only.empty() && !only.count(scene.name)) {
                continue;
            }
            for (const auto& point : points) {
                for (std::uint64_t seed : cfg.seeds) {
                    Task task;
                    task.index = index++;
                    task.scene = scene.name;
                    task.mode = modeName;
                    task.label = label;
                    task.settings = fixed;
                    task.settings.insert(task.settings.end(), point.begin(), point.end());
                    task.gridPoint = point;
                    task.seed = seed;
                    task.budget = budget;
                    task.frames = cfg.frames;
                    task.needsGpu = entry->needsGpu;
                    task.referenceSettings = referenceSettings;
                    if (budget.iterations) {
                        task.checkpoints = cfg.logCheckpoints ? logCheckpoints(budget.iterations) : cfg.checkpoints;
                        std::erase_if(task.checkpoints, [&](std::uint32_t c) { return c > budget.iterations; });
                        if (task.checkpoints.empty() || task.checkpoints.back() != budget.iterations) {
                            task.checkpoints.push_back(budget.iterations);
                        }
                    }
                    char prefix[16];
                    std::snprintf(prefix, sizeof(prefix), "%04u", task.index);
                    std::string params = describe(point);
                    task.id = sanitize(std::string(prefix) + "-" + scene.name + "-" + label +
                                       (params.empty() ? "" : "-" + params) + "-s" + std::to_string(seed));
                    std::string identity = scene.fingerprint + "|" + modeName + "|" + describe(task.settings) + "|" + std::to_string(seed) +
                                           "|" + std::to_string(budget.iterations) + "|" + formatNumber(budget.seconds) +
                                           "|" + describe(referenceSettings);
                    for (std::uint32_t c : task.checkpoints) identity += "," + std::to_string(c);
                    if (cfg.frames.frames > 1) { // a still keeps the hash it had before frame schedules
                        identity += "|frames " + std::to_string(cfg.frames.frames) + " at " +
                                    formatNumber(cfg.frames.frameRate);
                    }
                    task.hash = hashText(identity);
                    cfg.tasks.push_back(task);
                }
            }
        }
    }
    root.finish();
    return cfg;
}

} // namespace bl
