#include "reference/TexelBaker.h"

#include "atlas/TexelCoverage.h"
#include "base/Error.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <shared/Random.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bl {

namespace {

// A piece of a texel's footprint: the part of one atlas triangle inside the texel, fanned into
// triangles (uv in the page's texel units), each with its world area.
struct FootprintPiece {
    std::uint32_t mesh = 0;
    std::uint32_t triangle = 0;  // in the mesh (its corners in the mesh's order)
    glm::dvec2 corner[3];        // the whole atlas triangle's uv: the piece's barycentrics are relative to it
    glm::dvec2 piece[3];         // this fan triangle of the clipped polygon
    double worldArea = 0.0;
};

// Every valid texel's pieces, flattened: texel t owns pieces [first[t], first[t + 1]). The atlas's
// exchange divides by the same world areas (modes/atlas/AtlasTables.h), so sampling a piece by
// world area and a point uniformly in it is uniform over the texel's surface as the atlas sees it.
struct Footprints {
    std::vector<std::size_t> first;
    std::vector<FootprintPiece> pieces;
};

Footprints footprints(const atlas::Atlas& atlas) {
    const atlas::TexelMaps& maps = atlas.maps;
    std::vector<std::vector<std::uint32_t>> byTexel(maps.valid.size()); // indices into `all`
    std::vector<FootprintPiece> all;
    const glm::dvec2 size(maps.width, maps.height);
    for (std::size_t m = 0; m < atlas.meshes.size(); ++m) {
        const Mesh& mesh = atlas.meshes[m];
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
            const glm::uvec3 tri = mesh.triangles[i];
            FootprintPiece f;
            f.mesh = static_cast<std::uint32_t>(m);
            f.triangle = atlas.triangleSources[m][i];
            for (int k = 0; k < 3; ++k) f.corner[k] = glm::dvec2(mesh.uvs[tri[k]]) * size;
            const double uvArea = 0.5 * std::abs((f.corner[1].x - f.corner[0].x) * (f.corner[2].y - f.corner[0].y) -
                                                 (f.corner[2].x - f.corner[0].x) * (f.corner[1].y - f.corner[0].y));
            if (!(uvArea > 0.0)) continue; // no texel holds it (the atlas exchanges none of its hits either)
            const glm::dvec3 p0(mesh.positions[tri.x]), p1(mesh.positions[tri.y]), p2(mesh.positions[tri.z]);
            const double density = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0)) / uvArea; // world area per uv area
            const std::uint32_t page = atlas.vertexPages[m][tri.x];
            const glm::dvec2 lo = glm::min(f.corner[0], glm::min(f.corner[1], f.corner[2]));
            const glm::dvec2 hi = glm::max(f.corner[0], glm::max(f.corner[1], f.corner[2]));
            for (int y = std::max(0, int(std::floor(lo.y))); y <= std::min(maps.height - 1, int(std::floor(hi.y))); ++y) {
                for (int x = std::max(0, int(std::floor(lo.x))); x <= std::min(maps.width - 1, int(std::floor(hi.x))); ++x) {
                    const std::size_t t = (std::size_t(page) * maps.height + y) * maps.width + x;
                    if (maps.valid[t] != 1) continue;
                    const std::vector<glm::dvec2> poly = atlas::clipTriangleToTexel(f.corner[0], f.corner[1], f.corner[2], x, y);
                    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
                        f.piece[0] = poly[0];
                        f.piece[1] = poly[k];
                        f.piece[2] = poly[k + 1];
                        f.worldArea = density * atlas::polygonArea({poly[0], poly[k], poly[k + 1]});
                        if (!(f.worldArea > 0.0)) continue;
                        byTexel[t].push_back(static_cast<std::uint32_t>(all.size()));
                        all.push_back(f);
                    }
                }
            }
        }
    }
    Footprints out;
    out.first.reserve(byTexel.size() + 1);
    out.pieces.reserve(all.size());
    for (const std::vector<std::uint32_t>& list : byTexel) {
        out.first.push_back(out.pieces.size());
        for (std::uint32_t i : list) out.pieces.push_back(all[i]);
    }
    out.first.push_back(out.pieces.size());
    return out;
}

// Barycentrics (of corners 1 and 2) of q in triangle p.
glm::dvec2 barycentric(const glm::dvec2 p[3], glm::dvec2 q) {
    const glm::dvec2 e0 = p[1] - p[0], e1 = p[2] - p[0], e2 = q - p[0];
    const double det = e0.x * e1.y - e0.y * e1.x;
    return {(e2.x * e1.y - e2.y * e1.x) / det, (e0.x * e2.y - e0.y * e2.x) / det};
}

// The random stream of the point draws: apart from the paths' (seed, 2 texel + side, sample).
constexpr std::uint32_t kFootprintStream = 0x9e3779b9u;

} // namespace

TexelBake bakeTexels(const Scene& scene, const atlas::Atlas& atlas, const TexelBakeSettings& settings) {
    if (settings.samples == 0) {
        throw Error("texel bake: 0 samples per texel side");
    }
    if (scene.features().animated) {
        throw Error("texel bake: the scene is animated; an atlas's texels are baked for a static scene");
    }
    const auto start = std::chrono::steady_clock::now();
    const ReferenceRenderer renderer(scene, 0.0, settings.reference);
    const EmbreeScene& geometry = renderer.geometry();
    const PathTracer& tracer = renderer.tracer();
    const Footprints footprint = footprints(atlas);

    TexelBake out;
    out.radiance = atlas::TexelRadiance::like(atlas.maps);
    std::atomic<std::uint64_t> rays{0}, paths{0}, nonFinite{0}, empty{0};
    const auto texels = static_cast<std::int64_t>(atlas.maps.valid.size());
    auto bake = [&](const tbb::blocked_range<std::int64_t>& range) {
        std::uint64_t localRays = 0, localPaths = 0, localBad = 0, localEmpty = 0;
        for (std::int64_t t = range.begin(); t < range.end(); ++t) {
            if (!out.radiance.valid[t]) continue;
            const std::size_t begin = footprint.first[t], end = footprint.first[t + 1];
            if (begin == end) { // it touches triangles only along an edge: no surface, as in the atlas
                ++localEmpty;
                continue;
            }
            double total = 0.0;
            for (std::size_t i = begin; i < end; ++i) total += footprint.pieces[i].worldArea;
            glm::dvec3 sum[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
            std::uint32_t finite[2] = {0, 0};
            for (std::uint32_t s = 0; s < settings.samples; ++s) {
                shader::RandomStream rng =
                    shader::blRandomStream(settings.seed ^ kFootprintStream, static_cast<std::uint32_t>(t), s);
                // A piece by world area, then a uniform point in it.
                double pick = double(shader::blRandom(rng)) * total;
                std::size_t i = begin;
                while (i + 1 < end && pick >= footprint.pieces[i].worldArea) pick -= footprint.pieces[i++].worldArea;
                const FootprintPiece& f = footprint.pieces[i];
                const glm::vec2 r = shader::blRandom2(rng);
                const double su = std::sqrt(double(r.x));
                const glm::dvec2 q = (1.0 - su) * f.piece[0] + su * (1.0 - r.y) * f.piece[1] + su * r.y * f.piece[2];
                // Inside the triangle up to rounding: clamped back onto it (u, v >= 0, u + v <= 1).
                glm::dvec2 b = glm::max(barycentric(f.corner, q), 0.0);
                if (b.x + b.y > 1.0) b /= b.x + b.y;
                const SurfaceHit at = geometry.surfaceAt(f.mesh, f.triangle, float(b.x), float(b.y));
                for (int side = 0; side < 2; ++side) {
                    const auto stream = static_cast<std::uint32_t>(2 * t + side);
                    const PathSample p = tracer.traceLeaving(at, side == 1, stream, s, settings.seed);
                    localRays += p.rays;
                    ++localPaths;
                    if (!p.finite()) {
                        ++localBad;
                        continue;
                    }
                    sum[side] += glm::dvec3(p.total() - p.layers[0]);
                    ++finite[side];
                }
            }
            for (int side = 0; side < 2; ++side) {
                out.radiance.side[side][t] = finite[side] ? glm::vec3(sum[side] / double(finite[side])) : glm::vec3(0.0f);
            }
        }
        rays += localRays;
        paths += localPaths;
        nonFinite += localBad;
        empty += localEmpty;
    };
    const int threads = settings.reference.threads > 0 ? settings.reference.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, texels, 64), bake); });
    out.rays = rays;
    out.paths = paths;
    out.nonFiniteSamples = nonFinite;
    out.emptyTexels = empty;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace bl
