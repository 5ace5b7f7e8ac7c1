// bundlelab bench texels SCENE [--set k=v ...] [--directions N ...] [--bake-spp N ...]
//                              [--reference-spp N] [--image-spp N ...] [--views V ...] [--csv FILE] [--exr FILE]
//
// A benchmark, not a test: the atlas mode judged where it is meant to win. Its solution lives in
// the atlas, so its error is measured over every texel side against a texel-space reference (the
// path tracer baking the same texels at --reference-spp: reference/TexelBaker.h) and set against
// the baker itself at equal time; then, through the camera, against the path tracer rendering
// V views (the atlas solves once and resolves each view; the path tracer renders each view anew).
// Times: wall clock on this machine, the atlas's set-up (atlas build, uploads) apart from its
// iterations; read-backs and resolves are not counted in the iteration time but reported.
#include "atlas/TexelRadiance.h"
#include "base/Error.h"
#include "base/Log.h"
#include "cli/Commands.h"
#include "cli/Median.h"
#include "image/ImageIO.h"
#include "image/Metrics.h"
#include "modes/Registry.h"
#include "modes/atlas/AtlasMode.h"
#include "reference/ReferenceRenderer.h"
#include "reference/TexelBaker.h"
#include "scene/SceneLoader.h"
#include "vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bl::cli {

namespace {

struct TexelBenchOptions {
    std::string scene;
    std::vector<std::string> assignments;
    std::vector<std::uint32_t> directions{16, 64, 256, 1024};
    std::vector<std::uint32_t> bakeSpp{1, 4, 16, 64};
    std::uint32_t referenceSpp = 1024;
    std::vector<std::uint32_t> imageSpp{1, 4, 16, 64, 256};
    std::uint32_t imageReferenceSpp = 4096;
    std::vector<std::uint32_t> views{1, 4, 16};
    std::vector<double> targets{1e-1, 1e-2, 1e-3};
    std::string csv;
    std::string exr;
    std::string device;
    int width = 0, height = 0; // the camera's, when given
};

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// One point of an error-against-time curve.
struct Point {
    std::string method;
    std::uint32_t budget = 0; // spp or directions
    double seconds = 0.0;
    double texelRelMse = std::numeric_limits<double>::quiet_NaN();
    double imageRelMse = std::numeric_limits<double>::quiet_NaN();
};

// The time at which `curve` (points in time order) first reaches `target`, interpolated in
// log(time)-log(error) between the points that bracket it; nullopt where it never does.
std::optional<double> timeTo(const std::vector<Point>& curve, double Point::*error, double target) {
    for (std::size_t i = 0; i < curve.size(); ++i) {
        const double e = curve[i].*error;
        if (!(e <= target)) continue;
        if (i == 0 || !(curve[i - 1].*error > 0.0) || !(e > 0.0) || !(curve[i - 1].seconds > 0.0)) {
            return curve[i].seconds;
        }
        const double e0 = curve[i - 1].*error, t0 = curve[i - 1].seconds, t1 = curve[i].seconds;
        const double f = (std::log(target) - std::log(e0)) / (std::log(e) - std::log(e0));
        return std::exp(std::log(t0) + f * (std::log(t1) - std::log(t0)));
    }
    return std::nullopt;
}

// Refuses an output path that cannot be written before any work starts (nothing computed is lost
// to a typo at the end).
void requireOutputDirectory(const std::string& path, const char* option) {
    const std::filesystem::path parent = std::filesystem::absolute(path).parent_path();
    if (!std::filesystem::is_directory(parent)) {
        throw Error(std::string("bench texels: ") + option + " " + path + ": the directory " + parent.string() +
                    " does not exist");
    }
}

std::string formatSeconds(std::optional<double> s) {
    if (!s) return "not reached";
    char b[32];
    std::snprintf(b, sizeof b, "%.3g s", *s);
    return b;
}

int runBenchTexels(TexelBenchOptions o) {
    // Checkpoints in the order they are reached (timeTo reads each curve in time order).
    for (std::vector<std::uint32_t>* list : {&o.directions, &o.bakeSpp, &o.imageSpp}) {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    std::ofstream csv;
    if (!o.csv.empty()) {
        requireOutputDirectory(o.csv, "--csv");
        csv.open(o.csv);
        if (!csv) throw Error("bench texels: --csv " + o.csv + ": cannot be written");
    }
    if (!o.exr.empty()) {
        requireOutputDirectory(o.exr, "--exr");
        if (std::filesystem::path(o.exr).extension() != ".exr") {
            throw Error("bench texels: --exr " + o.exr + ": the file must end in .exr");
        }
    }
    Scene scene = loadScene(o.scene);
    if (o.width > 0) scene.camera.resolution.x = o.width;
    if (o.height > 0) scene.camera.resolution.y = o.height;
    if (scene.features().animated) {
        throw Error("bench texels: " + o.scene + " is animated; the texel-space reference bakes one moment");
    }
    vk::Context ctx(vk::ContextOptions{o.device, false}); // before the mode: it outlives the mode's state
    std::unique_ptr<Mode> mode = createMode("atlas", o.assignments);
    auto& atlasMode = static_cast<AtlasMode&>(*mode);
    std::printf("device: %s\nscene: %s, %zu triangles\n", ctx.info().describe().c_str(), o.scene.c_str(),
                scene.triangleCount());

    auto t = Clock::now();
    mode->setScene(scene, &ctx);
    const double setupSeconds = secondsSince(t);
    const atlas::TexelMaps& maps = atlasMode.texelMaps();
    std::size_t validTexels = 0;
    for (std::uint8_t v : maps.valid) validTexels += v == 1;
    std::printf("atlas: %dx%d x %d page(s), %zu texels with a sample of their own; set-up %.2f s\n", maps.width,
                maps.height, maps.pages, validTexels, setupSeconds);

    // The references: the texels baked, the camera's image rendered, each at a high count with a
    // seed none of the curves uses, and the path length the atlas keeps (max_segments with
    // transfer = bounce), so that its truncation is not counted as its error.
    constexpr std::uint32_t kReferenceSeed = 0x7e1e1u;
    ReferenceSettings paths;
    if (const std::int64_t segments = mode->settings().getInt(AtlasMode::kMaxSegments); segments > 0) {
        paths.path.maxSegments = static_cast<int>(segments);
    }
    if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.glossy(); })) {
        log::warn("bench texels: the scene has glossy materials; an atlas texel holds the diffuse exchange only "
                  "and the bake sees each lobe along the normal: their texels are not the same quantity");
    }
    TexelBakeSettings bake;
    bake.reference = paths;
    bake.samples = o.referenceSpp;
    bake.seed = kReferenceSeed;
    const TexelBake reference = bakeTexels(scene, atlasMode.atlas(), bake);
    std::printf("texel reference: %u paths per texel side, %.2f s, %llu non-finite samples left out, %llu texels "
                "without covered area\n",
                o.referenceSpp, reference.seconds, static_cast<unsigned long long>(reference.nonFiniteSamples),
                static_cast<unsigned long long>(reference.emptyTexels));
    const auto lit = [](const std::vector<glm::vec3>& side) {
        return std::any_of(side.begin(), side.end(), [](const glm::vec3& v) { return v != glm::vec3(0.0f); });
    };
    if (!lit(reference.radiance.side[0]) && !lit(reference.radiance.side[1])) {
        throw Error("bench texels: " + o.scene + ": no texel reflects any light (nothing lights the scene's surfaces)");
    }
    ReferenceRenderer imageReference(scene, 0.0, paths);
    t = Clock::now();
    for (std::uint32_t s = 0; s < o.imageReferenceSpp; ++s) imageReference.renderPass(s, kReferenceSeed);
    const Image referenceImage = imageReference.mean();
    std::printf("image reference: %u spp at %dx%d, %.2f s\n", o.imageReferenceSpp, referenceImage.width(),
                referenceImage.height(), secondsSince(t));

    std::vector<Point> baker, atlas, pathTracer;
    bake.samples = 1;
    bakeTexels(scene, atlasMode.atlas(), bake); // warm-up: the first bake's thread pool start is no baker's cost
    for (std::uint32_t spp : o.bakeSpp) {
        bake.samples = spp;
        bake.seed = 1;
        const TexelBake b = bakeTexels(scene, atlasMode.atlas(), bake);
        baker.push_back({"baker", spp, b.seconds, texelMetrics(b.radiance, reference.radiance).relMse});
    }
    ReferenceRenderer renderer(scene, 0.0, paths);
    double renderSeconds = 0.0;
    std::uint32_t rendered = 0;
    for (std::uint32_t spp : o.imageSpp) {
        t = Clock::now();
        for (; rendered < spp; ++rendered) renderer.renderPass(rendered, 1);
        renderSeconds += secondsSince(t);
        Point p{"path tracer", spp, renderSeconds};
        p.imageRelMse = computeMetrics(renderer.mean(), referenceImage).relMse;
        pathTracer.push_back(p);
    }
    double iterateSeconds = 0.0;
    std::uint32_t done = 0;
    std::vector<double> resolveSeconds;
    atlas::TexelRadiance last;
    for (std::uint32_t n : o.directions) {
        t = Clock::now();
        for (; done < n; ++done) {
            IterationInfo info;
            info.index = done;
            info.seed = 1;
            mode->iterate(info);
        }
        iterateSeconds += secondsSince(t);
        Point p{"atlas", n, setupSeconds + iterateSeconds};
        last = atlasMode.texelRadiance();
        p.texelRelMse = texelMetrics(last, reference.radiance).relMse;
        t = Clock::now();
        const ImageSet view = mode->resolve();
        resolveSeconds.push_back(secondsSince(t));
        p.imageRelMse = computeMetrics(view.radiance(), referenceImage).relMse;
        atlas.push_back(p);
    }
    const double perView = median(resolveSeconds);
    // Where the last atlas's error lies: the charts' border texels (partly covered, the surface's
    // edge through them) against the interior.
    const std::vector<std::uint8_t> border = atlas::chartBorder(maps);
    std::vector<std::uint8_t> interior(border.size());
    for (std::size_t i = 0; i < border.size(); ++i) interior[i] = !border[i];

    std::printf("\n| method | budget | seconds | texel relMSE | image relMSE |\n|---|---|---|---|---|\n");
    if (csv.is_open()) csv << "method,budget,seconds,texel_relmse,image_relmse\n";
    for (const std::vector<Point>* curve : {&baker, &atlas, &pathTracer}) {
        for (const Point& p : *curve) {
            std::printf("| %s | %u %s | %.3f | %.4g | %.4g |\n", p.method.c_str(), p.budget,
                        p.method == "atlas" ? "directions" : "spp", p.seconds, p.texelRelMse, p.imageRelMse);
            if (csv.is_open()) csv << p.method << "," << p.budget << "," << p.seconds << "," << p.texelRelMse << "," << p.imageRelMse << "\n";
        }
    }
    std::printf("\natlas resolve per view: %.3f s (median of %zu)\n", perView, resolveSeconds.size());
    const bool someBorder = std::any_of(border.begin(), border.end(), [](std::uint8_t b) { return b != 0; });
    const bool someInterior = std::any_of(interior.begin(), interior.end(), [](std::uint8_t b) { return b != 0; });
    if (someBorder && someInterior) {
        const ImageMetrics edge = atlas::texelMetrics(last, reference.radiance, border);
        const ImageMetrics inner = atlas::texelMetrics(last, reference.radiance, interior);
        std::printf("atlas at %u directions, texel relMSE on the charts' border texels %.4g (mean ratio %.4f), "
                    "inside %.4g (mean ratio %.4f)\n",
                    o.directions.back(), edge.relMse, edge.meanRatio.x, inner.relMse, inner.meanRatio.x);
    }
    std::printf("\nTime to texel relMSE (every texel side; atlas includes its %.2f s set-up):\n", setupSeconds);
    std::printf("| target | atlas | baker |\n|---|---|---|\n");
    for (double target : o.targets) {
        std::printf("| %g | %s | %s |\n", target, formatSeconds(timeTo(atlas, &Point::texelRelMse, target)).c_str(),
                    formatSeconds(timeTo(baker, &Point::texelRelMse, target)).c_str());
    }
    std::printf("\nTime to image relMSE for V views (atlas: solve once + V resolves; path tracer: V renders):\n");
    std::printf("| target | views | atlas | path tracer |\n|---|---|---|---|\n");
    for (double target : o.targets) {
        const std::optional<double> a = timeTo(atlas, &Point::imageRelMse, target);
        const std::optional<double> p = timeTo(pathTracer, &Point::imageRelMse, target);
        for (std::uint32_t v : o.views) {
            std::printf("| %g | %u | %s | %s |\n", target, v,
                        formatSeconds(a ? std::optional<double>(*a + v * perView) : std::nullopt).c_str(),
                        formatSeconds(p ? std::optional<double>(*p * v) : std::nullopt).c_str());
        }
    }
    if (!o.exr.empty()) {
        const auto mine = atlas::texelImages(last), truth = atlas::texelImages(reference.radiance);
        const std::vector<ImageLayer> layers{{"atlas." + mine[0].first, &mine[0].second},
                                             {"atlas." + mine[1].first, &mine[1].second},
                                             {"reference." + truth[0].first, &truth[0].second},
                                             {"reference." + truth[1].first, &truth[1].second}};
        writeExr(o.exr, layers);
        std::printf("wrote %s\n", o.exr.c_str());
    }
    return 0;
}

} // namespace

void addBenchTexelsCommand(CLI::App& bench, Action& action) {
    auto o = std::make_shared<TexelBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "texels", "atlas error over every texel against the path tracer baking the same texels, and per view");
    cmd->add_option("scene", o->scene, "scene file")->required();
    cmd->add_option("--set", o->assignments, "atlas mode parameter key=value (repeatable)");
    cmd->add_option("--directions", o->directions, "atlas checkpoints: directions done (repeatable, increasing)")
        ->check(CLI::Range(1u, 1u << 24));
    cmd->add_option("--bake-spp", o->bakeSpp, "baker checkpoints: paths per texel side (repeatable)")
        ->check(CLI::Range(1u, 1u << 20));
    cmd->add_option("--reference-spp", o->referenceSpp, "paths per texel side of the texel-space reference")
        ->check(CLI::Range(1u, 1u << 24));
    cmd->add_option("--image-spp", o->imageSpp, "path tracer checkpoints: spp of the camera's image (repeatable, increasing)")
        ->check(CLI::Range(1u, 1u << 24));
    cmd->add_option("--image-reference-spp", o->imageReferenceSpp, "spp of the camera's reference image")
        ->check(CLI::Range(1u, 1u << 24));
    cmd->add_option("--views", o->views, "view counts for the per-view comparison (repeatable)")->check(CLI::Range(1u, 1u << 20));
    cmd->add_option("--target", o->targets, "relMSE targets (repeatable)")->check(CLI::Range(1e-12, 1e6));
    cmd->add_option("--csv", o->csv, "also write every checkpoint as CSV");
    cmd->add_option("--exr", o->exr, "also write the atlas's last and the reference's texel sides (layers atlas.front ...)");
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring");
    cmd->add_option("--width", o->width, "camera image width (default: the scene's)")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", o->height, "camera image height (default: the scene's)")->check(CLI::Range(1, 16384));
    cmd->callback([o, &action] { action = [o] { return runBenchTexels(*o); }; });
}

} // namespace bl::cli
