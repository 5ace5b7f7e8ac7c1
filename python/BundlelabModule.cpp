// `import bundlelab`: the toolkit from Python (pybind11, built by the same CMake as the CLI).
//   scene = bundlelab.load_scene(path)            any format the CLI reads (TOML, OBJ/PLY, .xml, .gltf/.glb)
//   images = bundlelab.render(scene, mode, settings={}, iterations=None, seconds=None, seed=1,
//                             width=None, height=None)
//       -> {"radiance": float32 array (height, width, 3), every other layer by name, "counters": {...},
//           "iterations": n, "seconds": wall seconds of iterate()}
//   bundlelab.compare(test, reference, block=0)    the CLI's metrics (`bundlelab compare`) as a dict
//   bundlelab.modes()                             every mode with its parameter specs
//   bundlelab.run(config, out=None, jobs=1)        an experiment, as `bundlelab run`; returns failures
// Rendering releases the GIL; errors are Python exceptions (RuntimeError) with the CLI's messages.
// One Vulkan device per process, opened on the first GPU render (BUNDLELAB_DEVICE picks it, as
// --device does).
#include "base/Error.h"
#include "base/Log.h"
#include "image/Metrics.h"
#include "modes/FrameSchedule.h"
#include "modes/LostWork.h"
#include "modes/Registry.h"
#include "modes/SettingTrades.h"
#include "runner/Experiment.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>

namespace py = pybind11;

namespace {

using namespace bl;

// The process's Vulkan device: opened once (its creation costs more than a small render).
vk::Context& deviceContext() {
    static std::mutex mutex;
    static std::unique_ptr<vk::Context> context;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!context) {
        const char* device = std::getenv("BUNDLELAB_DEVICE");
        context = std::make_unique<vk::Context>(vk::ContextOptions{device ? device : "", false});
    }
    return *context;
}

// A Python value as the text a `--set key=value` takes.
std::string settingText(const py::handle& value) {
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    return py::str(value).cast<std::string>();
}

py::array_t<float> arrayOf(const Image& image) {
    py::array_t<float> out({image.height(), image.width(), 3});
    float* p = out.mutable_data();
    for (const glm::vec3& c : image.pixels()) {
        *p++ = c.x;
        *p++ = c.y;
        *p++ = c.z;
    }
    return out;
}

Image imageOf(const py::array_t<float, py::array::c_style | py::array::forcecast>& array, const char* what) {
    if (array.ndim() != 3 || array.shape(2) != 3) {
        throw Error(std::string(what) + ": an array of shape (height, width, 3) is needed");
    }
    Image image(int(array.shape(1)), int(array.shape(0)));
    const float* p = array.data();
    for (glm::vec3& c : image.pixels()) {
        c = glm::vec3(p[0], p[1], p[2]);
        p += 3;
    }
    return image;
}

struct RenderResult {
    ImageSet images;
    std::uint32_t iterations = 0;
    double seconds = 0.0;
};

RenderResult renderScene(Scene scene, const std::string& modeName, const std::vector<std::string>& assignments,
                         std::uint32_t iterations, double seconds, std::uint64_t seed) {
    using Clock = std::chrono::steady_clock;
    const ModeEntry& entry = findMode(modeName);
    std::unique_ptr<Mode> mode = createMode(modeName, assignments); // bad settings fail before any work
    vk::Context* ctx = entry.needsGpu ? &deviceContext() : nullptr;
    for (const std::string& w : lightsLeftOut(*mode, scene)) log::warn(w);
    for (const std::string& w : settingTrades(*mode, scene)) log::warn(w);
    mode->setScene(scene, ctx);
    const FrameSchedule schedule{};
    RenderResult r;
    while (iterations ? r.iterations < iterations : r.seconds < seconds) {
        const auto start = Clock::now();
        mode->iterate(schedule.iteration(0, r.iterations, seed));
        r.seconds += std::chrono::duration<double>(Clock::now() - start).count();
        ++r.iterations;
    }
    r.images = mode->resolve();
    const LostWorkVerdict lost = judgeLostWork(modeName, r.images);
    for (const std::string& w : lost.warnings) log::warn(w);
    if (!lost.refusal.empty()) throw Error(lost.refusal);
    return r;
}

py::object valueOf(const ParamValue& v) {
    return std::visit([](const auto& x) -> py::object { return py::cast(x); }, v);
}

} // namespace

namespace {
// A settings dict as the CLI's key=value assignments.
std::vector<std::string> assignmentsOf(const py::dict& settings) {
    std::vector<std::string> out;
    for (const auto& [key, value] : settings) out.push_back(settingText(key) + "=" + settingText(value));
    return out;
}
} // namespace

PYBIND11_MODULE(bundlelab, m) {
    m.doc() = "bundlelab: global illumination with global ray-bundles (Vulkan), its reference path tracer, metrics "
              "and experiment runner";
    py::register_exception<Error>(m, "Error", PyExc_RuntimeError);

    py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
        .def_readonly("path", &Scene::path)
        .def_property_readonly("triangles", &Scene::triangleCount)
        .def_property_readonly("lights", [](const Scene& s) { return s.lights.size(); })
        .def_property(
            "resolution", [](const Scene& s) { return std::make_pair(s.camera.resolution.x, s.camera.resolution.y); },
            [](Scene& s, std::pair<int, int> r) {
                if (r.first <= 0 || r.second <= 0) throw Error("resolution must be positive");
                s.camera.resolution = {r.first, r.second};
            })
        .def_readonly("import_notes", &Scene::importNotes)
        .def("__repr__", [](const Scene& s) {
            return "<bundlelab.Scene '" + s.path + "': " + std::to_string(s.triangleCount()) + " triangles, " +
                   std::to_string(s.camera.resolution.x) + "x" + std::to_string(s.camera.resolution.y) + ">";
        });

    m.def(
        "load_scene", [](const std::string& path) { return std::make_shared<Scene>(loadScene(path)); },
        py::arg("path"), "Loads a scene (TOML, OBJ/PLY, Mitsuba .xml, glTF .gltf/.glb).");

    m.def(
        "render",
        [](const Scene& scene, const std::string& mode, const py::dict& settings, std::optional<std::uint32_t> iterations,
           std::optional<double> seconds, std::uint64_t seed, std::optional<int> width, std::optional<int> height) {
            const std::vector<std::string> assignments = assignmentsOf(settings);
            if (iterations && seconds) throw Error("render: give iterations or seconds, not both");
            if (seconds && !(*seconds > 0.0 && std::isfinite(*seconds))) throw Error("render: seconds must be positive");
            Scene copy = scene;
            if (width) copy.camera.resolution.x = *width;
            if (height) copy.camera.resolution.y = *height;
            if (copy.camera.resolution.x <= 0 || copy.camera.resolution.y <= 0) throw Error("render: width and height must be positive");
            RenderResult r;
            {
                const py::gil_scoped_release release;
                r = renderScene(std::move(copy), mode, assignments, iterations.value_or(seconds ? 0u : 1u),
                                seconds.value_or(0.0), seed);
            }
            py::dict out;
            for (const auto& [name, image] : r.images.layers) out[py::str(name.empty() ? "radiance" : name)] = arrayOf(image);
            py::dict counters;
            for (const auto& [name, value] : r.images.counters) counters[py::str(name)] = value;
            out["counters"] = counters;
            out["iterations"] = r.iterations;
            out["seconds"] = r.seconds;
            return out;
        },
        py::arg("scene"), py::arg("mode"), py::arg("settings") = py::dict(), py::arg("iterations") = py::none(),
        py::arg("seconds") = py::none(), py::arg("seed") = 1, py::arg("width") = py::none(), py::arg("height") = py::none(),
        "Renders a scene with a mode: a dict of float32 layers (height, width, 3), counters, iterations, seconds.");

    m.def(
        "compare",
        [](const py::array_t<float, py::array::c_style | py::array::forcecast>& test,
           const py::array_t<float, py::array::c_style | py::array::forcecast>& reference, int block) {
            MetricOptions options;
            options.blockSize = block;
            const ImageMetrics e = computeMetrics(imageOf(test, "test"), imageOf(reference, "reference"), options);
            py::dict out;
            out["mse"] = e.mse;
            out["rmse"] = e.rmse;
            out["relmse"] = e.relMse;
            out["smape"] = e.smape;
            out["mae"] = e.mae;
            out["mean_ratio"] = py::make_tuple(e.meanRatio.x, e.meanRatio.y, e.meanRatio.z);
            out["block_ratio_rms"] = e.blockRatios.rms;
            return out;
        },
        py::arg("test"), py::arg("reference"), py::arg("block") = 0,
        "Error metrics of an image against a reference, as `bundlelab compare`.");

    m.def("modes", [] {
        py::list out;
        for (const ModeEntry& e : modeRegistry()) {
            py::list params;
            for (const ParamSpec& p : e.parameters()) {
                py::dict d;
                d["name"] = p.key;
                d["default"] = valueOf(p.defaultValue);
                d["unit"] = p.unit;
                d["help"] = p.help;
                if (std::isfinite(p.min)) d["min"] = p.min;
                if (std::isfinite(p.max)) d["max"] = p.max;
                if (!p.choices.empty()) d["choices"] = p.choices;
                params.append(d);
            }
            py::dict mode;
            mode["name"] = std::string(e.name);
            mode["summary"] = std::string(e.summary);
            mode["needs_gpu"] = e.needsGpu;
            mode["parameters"] = params;
            out.append(mode);
        }
        return out;
    }, "Every mode with its parameters (name, default, unit, help, min, max, choices).");

    m.def(
        "plan",
        [](const Scene& scene, const std::string& mode, const py::dict& settings) {
            const std::vector<std::string> assignments = assignmentsOf(settings);
            py::list out;
            for (const PlannedPass& p : createMode(mode, assignments)->plan(scene)) {
                py::dict d;
                d["id"] = p.id;
                d["name"] = p.name;
                d["runs"] = p.runs;
                d["code"] = p.code;
                d["reason"] = p.reason;
                d["light_left_out"] = p.lightLeftOut;
                out.append(d);
            }
            return out;
        },
        py::arg("scene"), py::arg("mode"), py::arg("settings") = py::dict(),
        "A mode's pass plan for a scene, as `bundlelab plan`: dicts of id, name, runs, code, reason, light_left_out.");

    m.def(
        "run",
        [](const std::string& config, std::optional<std::string> out, int jobs) {
            RunOptions options;
            options.outDir = out.value_or("");
            options.jobs = jobs;
            const py::gil_scoped_release release;
            return runExperiment(config, options);
        },
        py::arg("config"), py::arg("out") = py::none(), py::arg("jobs") = 1,
        "Runs an experiment config as `bundlelab run`; returns the number of failed tasks.");
}
