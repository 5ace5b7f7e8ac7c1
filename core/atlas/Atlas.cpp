#include "atlas/Atlas.h"

#include "atlas/AlbedoLookup.h"
#include "atlas/BuildProgress.h"
#include "atlas/Packing.h"
#include "atlas/TexelCoverage.h"
#include "base/Error.h"
#include "base/Log.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>

namespace bl::atlas {

namespace {

glm::vec3 corner(const Mesh& m, std::uint32_t f, int k) { return m.positions[m.triangles[f][k]]; }

// Flattens a face set, splitting it (in halves along its longest axis, then into connected
// parts) while the map flips a triangle or stretches beyond the bound.
void flattenSplitting(const Mesh& mesh, std::uint32_t meshIndex, const std::vector<std::uint32_t>& welded,
                      const std::vector<std::uint32_t>& faces, float maxStretch, std::vector<FlatChart>& out) {
    FlatChart c = flatten(mesh, meshIndex, faces, welded);
    if ((c.flipped == 0 && c.stretch <= maxStretch) || faces.size() == 1) {
        out.push_back(std::move(c));
        return;
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    std::vector<glm::vec3> centroid(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        centroid[i] = (corner(mesh, faces[i], 0) + corner(mesh, faces[i], 1) + corner(mesh, faces[i], 2)) / 3.0f;
        lo = glm::min(lo, centroid[i]);
        hi = glm::max(hi, centroid[i]);
    }
    const glm::vec3 e = hi - lo;
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    std::vector<std::size_t> order(faces.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::nth_element(order.begin(), order.begin() + order.size() / 2, order.end(),
                     [&](std::size_t a, std::size_t b) { return centroid[a][axis] < centroid[b][axis]; });
    std::vector<std::uint32_t> halves[2];
    for (std::size_t k = 0; k < order.size(); ++k) halves[k < order.size() / 2 ? 0 : 1].push_back(faces[order[k]]);
    for (const std::vector<std::uint32_t>& half : halves) {
        for (const std::vector<std::uint32_t>& part : connectedComponents(mesh, welded, half)) {
            flattenSplitting(mesh, meshIndex, welded, part, maxStretch, out);
        }
    }
}

// Rounds of giving texel-less triangles charts of their own before reporting them uncovered (one
// suffices: a chart of one triangle owns every texel it touches).
constexpr int kCoverageRounds = 2;

// Packings tried when searching the densest one that fits the atlas; the search ends earlier
// when a packing fills this fraction of the atlas's rows.
constexpr int kDensitySearchPackings = 6;
constexpr double kFullEnough = 0.995;

// The most texels an atlas may have over all its pages (65 bytes of maps each: 16 GiB).
constexpr std::size_t kMaxAtlasTexels = std::size_t(1) << 28;

// Scales and places the oriented charts: the densest packing into the first `fill` of the rows of
// one options.size^2 page (the rest left for the charts of sub-texel triangles, added after), or
// options.texelsPerUnit in the smallest power-of-two page that holds it, up to options.pageSize,
// then on as many such pages as needed. Returns the density; uv become page texel coordinates.
float packAtlas(std::vector<FlatChart>& charts, const AtlasOptions& options, double fill, int& width, int& height,
                int& pages, ProgressLog& progress) {
    double area = 0.0;
    for (const FlatChart& c : charts) {
        for (std::size_t i = 0; i < c.faces.size(); ++i) {
            const glm::vec2 a = c.uv[3 * i], b = c.uv[3 * i + 1], d = c.uv[3 * i + 2];
            area += 0.5 * std::abs((b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y));
        }
    }
    if (!(area > 0.0)) {
        throw Error("atlas: the scene has no surface area");
    }
    Packing packing;
    float density = options.texelsPerUnit;
    if (density > 0.0f) {
        if (options.pageSize < 64 || options.pageSize > 16384) {
            throw Error("atlas: page size " + std::to_string(options.pageSize) + " outside [64, 16384]");
        }
        const double needed = area * double(density) * density;
        if (!(needed < double(kMaxAtlasTexels))) {
            throw Error("atlas: " + formatNumber(density) + " texels per unit need over " + formatNumber(needed / 1048576.0) +
                        " M texels, more than the " + std::to_string(kMaxAtlasTexels >> 20) + " M an atlas may have");
        }
        for (width = 64; width < options.pageSize; width *= 2) {
            if (packCharts(charts, density, width, width, options.padding, 1, packing)) break;
        }
        width = std::min(width, options.pageSize);
        const int maxPages = int(kMaxAtlasTexels / (std::size_t(width) * width));
        if (packing.pageCount == 0 && !packCharts(charts, density, width, width, options.padding, maxPages, packing)) {
            throw Error("atlas: at " + formatNumber(density) + " texels per unit a chart is larger than a " +
                        std::to_string(width) + "^2 page, or the charts need over " + std::to_string(maxPages) + " pages");
        }
        height = width;
    } else {
        width = height = options.size;
        if (width < 16 || width > 16384) throw Error("atlas: size " + std::to_string(width) + " outside [16, 16384]");
        // Pack into an atlas of unbounded height and scale the density by the root of the height
        // ratio: the area a packing takes grows with the density squared, so a few packings reach
        // the densest that fits. Start from the density that would cover 3/4 of the atlas.
        constexpr int kUnbounded = std::numeric_limits<int>::max() / 4;
        const int rows = std::max(1, int(fill * height));
        double fits = 0.0, trial = std::sqrt(0.75 * double(width) * rows / area);
        Packing attempt;
        for (int i = 0; i < kDensitySearchPackings || fits == 0.0; ++i) {
            int used = 2 * rows; // a chart wider than the atlas: shrink
            if (packCharts(charts, float(trial), width, kUnbounded, options.padding, 1, attempt)) used = attempt.usedHeight;
            log::debug("atlas: " + std::to_string(trial) + " texels per unit take " + std::to_string(used) + " rows");
            progress.say([&] {
                char text[32];
                std::snprintf(text, sizeof(text), "%.4g", trial);
                return "packing " + std::to_string(charts.size()) + " charts, density search step " + std::to_string(i + 1) +
                       " (" + text + " texels per unit take " + std::to_string(used) + " of " + std::to_string(rows) +
                       " rows)";
            });
            if (used <= rows && trial > fits) {
                fits = trial;
                packing = attempt;
                if (used >= kFullEnough * rows) break;
            }
            const double next = trial * std::sqrt(double(rows) / std::max(used, 1)) * (used <= rows ? 1.0 : 0.99);
            trial = next > fits ? next : 0.5 * (fits + trial);
            if (!(trial > 0.0) || i > 64) {
                throw Error("atlas: " + std::to_string(charts.size()) + " charts do not fit in " + std::to_string(width) +
                            "^2 texels with " + std::to_string(options.padding) + " texels padding");
            }
        }
        density = float(fits);
    }
    pages = packing.pageCount;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        placeChart(charts[c], density, packing.offsets[c], packing.turns[c]);
        charts[c].page = std::uint32_t(packing.pages[c]);
    }
    return density;
}

// One packing and covering of the charts (packAndCover).
struct Covered {
    std::vector<FlatChart> charts;
    std::vector<TexelOwner> owner;
    std::map<std::pair<int, int>, int> owned;
    float density = 0.0f;
    double fill = 1.0;
    int width = 0, height = 0, pages = 1;
    int packedPages = 1;         // pages of the packing, before the single-triangle charts
    double spilledTexels = 0.0;  // texels the single-triangle charts took on pages beyond those
    std::size_t isolatedTriangles = 0, uncoveredTriangles = 0;
    // This one where `keep`, else `other`.
    Covered keepIf(bool keep, Covered&& other) && { return keep ? std::move(*this) : std::move(other); }
};

// A packing that left single-triangle charts no room is packed again into fewer rows: at most
// this many times, where what spilled is under kRoomAtMost of a page, giving up kRoomMargin times
// the spilled texels (fewer rows mean a lower density, so more triangles fall under a texel).
constexpr int kRoomAttempts = 3;
constexpr double kRoomAtMost = 0.25;
constexpr double kRoomMargin = 2.0;

// The texels a single-triangle chart takes with its padding: its bounding box, its uv scaled by
// `texelsPerUv` (the density before placing, 1 once placed: uv are then page texels).
double singleFootprint(const FlatChart& chart, float texelsPerUv, int padding) {
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec2& q : chart.uv) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    const glm::vec2 texels = glm::ceil((hi - lo) * texelsPerUv) + 1.0f + 2.0f * float(padding);
    return double(texels.x) * double(texels.y);
}

// Charts of their own for sub-texel triangles cost texels in proportion to the triangles' extent,
// not their area: a scanned or detailed model's small triangles take a few pages (Sibenik and Sponza
// at 512^2: about 5 pages by the estimate below, the bunny 1), a floor of 20,000 slivers of aspect
// 1e4 hundreds (308 at 128^2) and a 1M-triangle floor thousands, where every such texel sees only
// its own triangle's few hits and placing them one by one takes minutes. Past
// AtlasOptions::singleChartPages (16) times the largest of a page, the rest of the scene's charts and
// a default 512^2 page (a budget of time and memory per iteration, well above what the real scenes
// need; the last keeps small atlases of 64^2 with a few thousand slivers, about 0.5 M texels,
// allowed), refused up front with the figures. A single's footprint is its bounding box at the atlas density plus its padding (an upper
// bound on the mask the packer places; about twice it for slivers).

// `needed` carries the texels of the singles of earlier coverage rounds: the budget is for all.
void refuseOutweighingSingles(const std::vector<FlatChart>& singles, float density, const AtlasOptions& options,
                              std::size_t occupied, int width, int height, std::size_t triangles, double& needed) {
    for (const FlatChart& c : singles) needed += singleFootprint(c, density, options.padding);
    const double page = double(width) * double(height);
    if (needed > options.singleChartPages * std::max({double(occupied), page, options.singleChartFloorTexels})) {
        throw Error("atlas: " + std::to_string(singles.size()) + " of the scene's " + std::to_string(triangles) +
                    " triangles are too thin or too small for a texel of their own at atlas_resolution " +
                    std::to_string(options.size) + " (slivers, or triangles crowded within a texel); charts of their "
                    "own would need up to about " + std::to_string(std::llround(needed / page)) + " pages (" +
                    std::to_string(std::llround(needed)) + " texels), more than " + std::to_string(std::llround(options.singleChartPages)) +
                    " times the rest of the scene's charts (" + std::to_string(occupied) +
                    "), a page or a 512^2 page: remesh them into fewer, fatter triangles, or raise "
                    "atlas_resolution until they own texels");
    }
}

// Packs the oriented charts (packAtlas, `fill` of the rows with a fixed side), then covers the
// texels: triangles left without a texel of their own (sub-texel slivers crowded by their
// neighbours) move to charts of their own, added into the holes of the finished atlas without
// moving anything else (on new pages where no hole holds them); alone, they own every texel they
// touch.
Covered packAndCover(const Scene& scene, const AtlasOptions& options, const std::vector<std::vector<std::uint32_t>>& welded,
                     const std::vector<FlatChart>& oriented, double fill, ProgressLog& progress) {
    std::size_t triangleCount = 0;
    for (const Mesh& m : scene.meshes) triangleCount += m.triangles.size();
    Covered out;
    out.charts = oriented;
    out.fill = fill;
    std::vector<FlatChart>& charts = out.charts;
    int& width = out.width;
    int& height = out.height;
    int& pages = out.pages;
    const float density = out.density = packAtlas(charts, options, fill, width, height, pages, progress);
    out.packedPages = pages;
    std::vector<ChartPacker> packers(std::size_t(pages), ChartPacker(width, height, options.padding));
    for (const FlatChart& c : charts) packers[c.page].occupy(c);
    std::size_t occupied = 0;
    for (const ChartPacker& p : packers) occupied += p.occupiedTexels();
    log::debug("atlas: charts take " + std::to_string(double(occupied) / (double(width) * height * pages)) +
               " of the atlas with their padding");
    double singleTexels = 0.0; // what the singles of every round need (refuseOutweighingSingles)
    for (int round = 0;; ++round) {
        progress.say([&] { return "covering texels, round " + std::to_string(round + 1); });
        std::vector<std::pair<std::size_t, std::size_t>> uncovered =
            coverTexels(charts, width, height, pages, out.owner, out.owned, progress);
        if (uncovered.empty() || round == kCoverageRounds) {
            out.uncoveredTriangles = uncovered.size();
            break;
        }
        log::debug("atlas: " + std::to_string(uncovered.size()) + " triangles own no texel; giving them charts of their own");
        out.isolatedTriangles += uncovered.size();
        std::sort(uncovered.begin(), uncovered.end(), std::greater<>());
        std::vector<FlatChart> singles;
        for (auto [c, i] : uncovered) {
            FlatChart& chart = charts[c];
            singles.push_back(flatten(scene.meshes[chart.mesh], chart.mesh, {chart.faces[i]}, welded[chart.mesh]));
            chart.faces.erase(chart.faces.begin() + std::ptrdiff_t(i));
            chart.uv.erase(chart.uv.begin() + std::ptrdiff_t(3 * i), chart.uv.begin() + std::ptrdiff_t(3 * i + 3));
        }
        std::erase_if(charts, [](const FlatChart& c) { return c.faces.empty(); });
        orientCharts(singles);
        refuseOutweighingSingles(singles, density, options, occupied, width, height, triangleCount, singleTexels);
        for (std::size_t k = 0; k < singles.size(); ++k) {
            FlatChart& single = singles[k];
            progress.say([&] {
                return "placing " + std::to_string(singles.size()) + " single-triangle charts into holes: " +
                       std::to_string(k + 1) + " placed";
            });
            glm::vec2 offset;
            int turns = 0;
            std::uint32_t page = 0;
            while (page < packers.size() && !packers[page].place(single, density, offset, turns)) ++page;
            if (page == packers.size()) {
                // No room left on any page: a new page (its triangle left out would leave the
                // atlas without it, and the atlas link refuse the scene).
                packers.emplace_back(width, height, options.padding);
                ++pages;
                if (!packers[page].place(single, density, offset, turns)) {
                    continue; // larger than a page: stays uncovered and is counted
                }
            }
            placeChart(single, density, offset, turns);
            single.page = page;
            if (int(page) >= out.packedPages) out.spilledTexels += singleFootprint(single, 1.0f, options.padding);
            charts.push_back(std::move(single));
        }
    }
    return out;
}

} // namespace

Atlas buildAtlas(const Scene& scene, const AtlasOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Atlas atlas;
    AtlasStats& st = atlas.stats;
    ProgressLog progress;

    // 1. Charts, flattened and split until valid.
    std::vector<std::vector<std::uint32_t>> welded(scene.meshes.size());
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        st.triangles += mesh.triangles.size();
        std::uint32_t distinct = 0;
        welded[m] = weldVertices(mesh, distinct);
        ChartingStats cs;
        for (const ChartFaces& c : growCharts(mesh, m, options.charting, cs)) {
            for (const std::vector<std::uint32_t>& part : connectedComponents(mesh, welded[m], c.faces)) {
                flattenSplitting(mesh, m, welded[m], part, options.maxStretch, atlas.charts);
            }
            progress.say([&] {
                return "flattening mesh " + std::to_string(m + 1) + " of " + std::to_string(scene.meshes.size()) + ": " +
                       std::to_string(atlas.charts.size()) + " charts so far";
            });
        }
        st.nonManifoldFaces += cs.nonManifoldFaces;
        st.degenerateFaces += cs.degenerateFaces;
    }
    orientCharts(atlas.charts);

    // 2-3. Pack, then cover texels (packAndCover). With a fixed side (options.size) the densest
    // packing fills the page, so the charts of sub-texel triangles, which only the covering finds,
    // spilled onto a page of their own (Sponza at 2048^2: a second, nearly empty page, utilization
    // 0.447). Where they would fit in part of a page, the charts are packed again into the rows
    // that leave them room (up to kRoomAttempts times), and the packing with fewer pages is kept.
    const std::vector<FlatChart> oriented = atlas.charts;
    Covered packed = packAndCover(scene, options, welded, oriented, 1.0, progress);
    const double page = double(packed.width) * double(packed.height);
    for (int attempt = 0; options.texelsPerUnit <= 0.0f && packed.pages > packed.packedPages &&
                          attempt < kRoomAttempts && packed.spilledTexels < kRoomAtMost * page;
         ++attempt) {
        const double fill = packed.fill - kRoomMargin * packed.spilledTexels / page;
        log::debug("atlas: " + std::to_string(packed.spilledTexels) + " texels of single-triangle charts spilled onto " +
                   std::to_string(packed.pages - packed.packedPages) + " more page(s); packing into " +
                   std::to_string(fill) + " of the rows");
        progress.say([&] { return "packing again to leave room for single-triangle charts"; });
        Covered again = packAndCover(scene, options, welded, oriented, fill, progress);
        const bool better = again.pages < packed.pages;
        packed = std::move(again).keepIf(better, std::move(packed));
        if (!better) break;
    }
    atlas.charts = std::move(packed.charts);
    st.isolatedTriangles += packed.isolatedTriangles;
    st.uncoveredTriangles = packed.uncoveredTriangles;
    const float density = packed.density;
    const int width = packed.width, height = packed.height, pages = packed.pages;
    std::vector<TexelOwner>& owner = packed.owner;
    std::map<std::pair<int, int>, int>& owned = packed.owned;
    atlas.texelsPerUnit = density;
    TexelMaps& maps = atlas.maps;
    maps.width = width;
    maps.height = height;
    maps.pages = pages;
    const std::size_t texels = std::size_t(width) * height * pages;

    // 4. Maps from the owners.
    maps.position.assign(texels, glm::vec3(0.0f));
    maps.normal.assign(texels, glm::vec3(0.0f));
    maps.material.assign(texels, 0);
    maps.emission.assign(texels, glm::vec3(0.0f));
    maps.albedo.assign(texels, glm::vec3(0.0f));
    maps.triangle.assign(texels, 0);
    maps.area.assign(texels, 0.0f);
    maps.valid.assign(texels, 0);
    maps.chart.assign(texels, -1);
    std::size_t covered = 0;
    const AlbedoLookup albedo(scene);
    const std::vector<std::uint32_t> firstTriangle = firstSceneTriangles(scene);
    for (std::size_t t = 0; t < texels; ++t) {
        const TexelOwner& o = owner[t];
        st.overlappingTexels += o.otherChart >= 0;
        if (o.chart < 0) continue;
        const FlatChart& chart = atlas.charts[o.chart];
        const Mesh& mesh = scene.meshes[chart.mesh];
        const std::uint32_t f = chart.faces[o.face];
        const glm::uvec3& tri = mesh.triangles[f];
        maps.position[t] = o.bary.x * mesh.positions[tri.x] + o.bary.y * mesh.positions[tri.y] + o.bary.z * mesh.positions[tri.z];
        glm::vec3 n = o.bary.x * mesh.normals[tri.x] + o.bary.y * mesh.normals[tri.y] + o.bary.z * mesh.normals[tri.z];
        maps.normal[t] = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
        maps.material[t] = mesh.material;
        maps.emission[t] = mesh.emission;
        const glm::vec2 materialUv = mesh.uvs.empty() ? glm::vec2(0.0f)
                                                      : o.bary.x * mesh.uvs[tri.x] + o.bary.y * mesh.uvs[tri.y] +
                                                            o.bary.z * mesh.uvs[tri.z];
        maps.albedo[t] = albedo.at(mesh.material, materialUv);
        maps.triangle[t] = firstTriangle[chart.mesh] + f;
        const float a3 = 0.5f * glm::length(glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                                       mesh.positions[tri.z] - mesh.positions[tri.x]));
        maps.area[t] = a3 / float(owned[{o.chart, o.face}]);
        maps.valid[t] = 1;
        maps.chart[t] = o.chart;
        ++covered;
    }
    // One ring of dilation, so bilinear lookups at chart borders never read empty texels.
    std::vector<std::uint8_t> before = maps.valid;
    for (int y = 0; y < height * pages; ++y) { // pages stacked: a page's rows never reach into the next
        for (int x = 0; x < width; ++x) {
            const std::size_t t = std::size_t(y) * width + x;
            if (before[t]) continue;
            for (int dy = -1; dy <= 1 && !maps.valid[t]; ++dy) {
                for (int dx = -1; dx <= 1 && !maps.valid[t]; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || nx >= width || ny < 0 || ny / height != y / height) continue; // same page only
                    const std::size_t s = std::size_t(ny) * width + nx;
                    if (before[s] != 1) continue;
                    maps.position[t] = maps.position[s];
                    maps.normal[t] = maps.normal[s];
                    maps.material[t] = maps.material[s];
                    maps.emission[t] = maps.emission[s];
                    maps.albedo[t] = maps.albedo[s];
                    maps.triangle[t] = maps.triangle[s];
                    maps.chart[t] = maps.chart[s];
                    maps.valid[t] = 2;
                }
            }
        }
    }

    // 5. Per-vertex atlas uvs (vertices split where charts meet) and the statistics.
    atlas.meshes.resize(scene.meshes.size());
    atlas.vertexPages.resize(scene.meshes.size());
    atlas.vertexSources.resize(scene.meshes.size());
    atlas.triangleSources.resize(scene.meshes.size());
    atlas.triangleCharts.resize(scene.meshes.size());
    std::vector<std::map<std::pair<std::uint32_t, std::size_t>, std::uint32_t>> vertexOf(scene.meshes.size());
    double stretchWeighted = 0.0, areaTotal = 0.0;
    for (std::size_t c = 0; c < atlas.charts.size(); ++c) {
        const FlatChart& chart = atlas.charts[c];
        const Mesh& mesh = scene.meshes[chart.mesh];
        Mesh& out = atlas.meshes[chart.mesh];
        double chartArea = 0.0;
        for (std::size_t i = 0; i < chart.faces.size(); ++i) {
            const glm::uvec3& tri = mesh.triangles[chart.faces[i]];
            chartArea += 0.5 * glm::length(glm::cross(mesh.positions[tri.y] - mesh.positions[tri.x],
                                                      mesh.positions[tri.z] - mesh.positions[tri.x]));
            glm::uvec3 split;
            for (int k = 0; k < 3; ++k) {
                auto [it, inserted] = vertexOf[chart.mesh].try_emplace({tri[k], c}, std::uint32_t(out.positions.size()));
                if (inserted) {
                    out.positions.push_back(mesh.positions[tri[k]]);
                    out.normals.push_back(mesh.normals[tri[k]]);
                    out.uvs.push_back(chart.uv[3 * i + k] / glm::vec2(float(width), float(height)));
                    atlas.vertexPages[chart.mesh].push_back(chart.page);
                    atlas.vertexSources[chart.mesh].push_back(tri[k]);
                }
                split[k] = it->second;
            }
            out.triangles.push_back(split);
            atlas.triangleSources[chart.mesh].push_back(chart.faces[i]);
            atlas.triangleCharts[chart.mesh].push_back(std::uint32_t(c));
        }
        stretchWeighted += chart.stretch * chartArea;
        areaTotal += chartArea;
        st.maxStretch = std::max(st.maxStretch, double(chart.stretch));
        st.flippedTriangles += chart.flipped;
    }
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& out = atlas.meshes[m];
        out.name = scene.meshes[m].name;
        out.material = scene.meshes[m].material;
        out.emission = scene.meshes[m].emission;
        out.animation = scene.meshes[m].animation;
    }
    st.charts = atlas.charts.size();
    st.pages = pages;
    st.meanStretch = areaTotal > 0.0 ? stretchWeighted / areaTotal : 1.0;
    st.utilization = double(covered) / double(texels);
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return atlas;
}

std::vector<std::uint32_t> firstSceneTriangles(const Scene& scene) {
    std::vector<std::uint32_t> first{0};
    for (const Mesh& m : scene.meshes) {
        const std::size_t next = std::size_t(first.back()) + m.triangles.size();
        if (next > std::numeric_limits<std::uint32_t>::max()) {
            throw Error("scene: " + std::to_string(next) + " triangles and more, over the 2^32 a triangle index holds");
        }
        first.push_back(std::uint32_t(next));
    }
    return first;
}

Image chartImage(const TexelMaps& maps) {
    Image img(maps.width, maps.height * maps.pages); // pages stacked top to bottom
    for (std::size_t t = 0; t < maps.valid.size(); ++t) {
        if (!maps.valid[t]) continue;
        std::uint32_t h = std::uint32_t(maps.chart[t]) * 2654435761u;
        glm::vec3 c(float((h >> 8) & 255) / 255.0f, float((h >> 16) & 255) / 255.0f, float((h >> 24) & 255) / 255.0f);
        c = 0.25f + 0.75f * c;
        img.pixels()[t] = maps.valid[t] == 1 ? c : 0.3f * c;
    }
    return img;
}

} // namespace bl::atlas
