// bundlelab atlas SCENE [--texels-per-unit X | --size N] --out atlas.png --report atlas.json
#include "atlas/Atlas.h"
#include "base/Error.h"
#include "base/Json.h"
#include "cli/Commands.h"
#include "cli/FiniteRange.h"
#include "image/ImageIO.h"
#include "scene/SceneLoader.h"

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

namespace bl::cli {

void addAtlasCommand(CLI::App& app, Action& action) {
    struct Options {
        std::string scene, out, report;
        atlas::AtlasOptions atlas;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("atlas", "build the texture atlas of a scene (charts, uvs, texel maps)");
    cmd->add_option("scene", o->scene, "scene file (.toml, Mitsuba 3 .xml, or a bare .obj/.ply)")->required();
    auto* tpu = cmd->add_option("--texels-per-unit", o->atlas.texelsPerUnit, "fixed texel density (the atlas grows)")
                    ->check(finiteRange(1e-9, 1e9));
    auto* size = cmd->add_option("--size", o->atlas.size, "atlas side in texels (density chosen to fill it)")
                     ->check(CLI::Range(16, 16384));
    tpu->excludes(size);
    cmd->add_option("--page-size", o->atlas.pageSize, "with --texels-per-unit: largest page side; more pages beyond")
        ->check(CLI::Range(64, 16384));
    cmd->add_option("--padding", o->atlas.padding, "texels between charts")->check(CLI::Range(2, 64));
    cmd->add_option("--cone", o->atlas.charting.coneDegrees, "charting normal cone (degrees)")
        ->check(finiteRange(1.0, 89.0));
    cmd->add_option("--seam-weight", o->atlas.charting.seamWeight, "charting cost of seam length against normal deviation")
        ->check(finiteRange(0.0, 100.0));
    cmd->add_option("--max-stretch", o->atlas.maxStretch, "split charts above this L2 stretch")
        ->check(finiteRange(1.0, 100.0));
    cmd->add_option("-o,--out", o->out, "PNG of the charts in colour");
    cmd->add_option("--report", o->report, "JSON report (utilization, charts, stretch, flips, overlaps, coverage)");
    cmd->callback([o, &action] {
        action = [o] {
            Scene scene = loadScene(o->scene);
            atlas::Atlas a = atlas::buildAtlas(scene, o->atlas);
            const atlas::AtlasStats& s = a.stats;
            std::printf("atlas of %s: %d page(s) of %dx%d, %.5g texels per unit, %zu charts over %zu triangles\n",
                        o->scene.c_str(), a.maps.pages, a.maps.width, a.maps.height, a.texelsPerUnit, s.charts, s.triangles);
            std::printf("utilization %.4f, stretch mean %.4f max %.4f, flipped %zu, overlapping texels %zu, "
                        "uncovered triangles %zu, non-manifold %zu, degenerate %zu, %.2f s\n",
                        s.utilization, s.meanStretch, s.maxStretch, s.flippedTriangles, s.overlappingTexels,
                        s.uncoveredTriangles, s.nonManifoldFaces, s.degenerateFaces, s.seconds);
            if (!o->out.empty()) {
                writePng(o->out, atlas::chartImage(a.maps));
                std::printf("wrote %s\n", o->out.c_str());
            }
            if (!o->report.empty()) {
                std::ostringstream j;
                JsonWriter w(j);
                w.beginObject().field("scene", o->scene).field("width", a.maps.width).field("height", a.maps.height);
                w.field("pages", a.maps.pages);
                w.field("texels_per_unit", double(a.texelsPerUnit)).field("utilization", s.utilization);
                w.field("charts", static_cast<unsigned long long>(s.charts));
                w.field("triangles", static_cast<unsigned long long>(s.triangles));
                w.field("mean_stretch", s.meanStretch).field("max_stretch", s.maxStretch);
                w.field("flipped_triangles", static_cast<unsigned long long>(s.flippedTriangles));
                w.field("overlapping_texels", static_cast<unsigned long long>(s.overlappingTexels));
                w.field("uncovered_triangles", static_cast<unsigned long long>(s.uncoveredTriangles));
                w.field("non_manifold_faces", static_cast<unsigned long long>(s.nonManifoldFaces));
                w.field("degenerate_faces", static_cast<unsigned long long>(s.degenerateFaces));
                w.field("padding", o->atlas.padding).field("seconds", s.seconds).endObject();
                std::ofstream(o->report) << j.str() << "\n";
                std::printf("wrote %s\n", o->report.c_str());
            }
            return 0;
        };
    });
}

} // namespace bl::cli
