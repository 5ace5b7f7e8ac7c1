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

// An atlas triangle touching a texel: its scene mesh and triangle, its corners in the page's texel
// units and on the surface.
struct FootprintTriangle {
    std::uint32_t mesh = 0;
    std::uint32_t triangle = 0; // in the mesh
    glm::vec2 uv[3];
    glm::vec3 position[3];
};

// Per texel, the atlas triangles that touch it (valid texels only), as the atlas's coverage finds
// them (atlas::overlapsTexel).
std::vector<std::vector<FootprintTriangle>> footprints(const atlas::Atlas& atlas) {
    const atlas::TexelMaps& maps = atlas.maps;
    std::vector<std::vector<FootprintTriangle>> out(maps.valid.size());
    const glm::vec2 size(float(maps.width), float(maps.height));
    for (std::size_t m = 0; m < atlas.meshes.size(); ++m) {
        const Mesh& mesh = atlas.meshes[m];
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
            const glm::uvec3 tri = mesh.triangles[i];
            FootprintTriangle f;
            f.mesh = static_cast<std::uint32_t>(m);
            f.triangle = atlas.triangleSources[m][i];
            for (int k = 0; k < 3; ++k) {
                f.uv[k] = mesh.uvs[tri[k]] * size;
                f.position[k] = mesh.positions[tri[k]];
            }
            const std::uint32_t page = atlas.vertexPages[m][tri.x];
            const glm::vec2 lo = glm::min(f.uv[0], glm::min(f.uv[1], f.uv[2]));
            const glm::vec2 hi = glm::max(f.uv[0], glm::max(f.uv[1], f.uv[2]));
            for (int y = std::max(0, int(std::floor(lo.y))); y <= std::min(maps.height - 1, int(std::floor(hi.y))); ++y) {
                for (int x = std::max(0, int(std::floor(lo.x))); x <= std::min(maps.width - 1, int(std::floor(hi.x))); ++x) {
                    const std::size_t t = (std::size_t(page) * maps.height + y) * maps.width + x;
                    if (maps.valid[t] == 1 && atlas::overlapsTexel(f.uv, float(x), float(y))) out[t].push_back(f);
                }
            }
        }
    }
    return out;
}

// Barycentrics of q in triangle p (2D); any negative: outside.
glm::vec3 barycentric(const glm::vec2 p[3], glm::vec2 q) {
    const glm::vec2 e0 = p[1] - p[0], e1 = p[2] - p[0], e2 = q - p[0];
    const float det = e0.x * e1.y - e0.y * e1.x;
    if (det == 0.0f) return glm::vec3(-1.0f);
    const float u = (e2.x * e1.y - e2.y * e1.x) / det, v = (e0.x * e2.y - e0.y * e2.x) / det;
    return {1.0f - u - v, u, v};
}

// Draws for a sample's point in the footprint, before giving the sample up as a miss (counted as
// no sample: the texel's mean is over the accepted ones). A texel whose coverage is a sliver of
// its square may need many; kMaxDraws keeps the cost bounded.
constexpr int kMaxDraws = 256;
// The random stream of the point draws: apart from the path's (seed, texel, sample) stream.
constexpr std::uint32_t kFootprintStream = 0x9e3779b9u;

} // namespace

TexelBake bakeTexels(const Scene& scene, const atlas::Atlas& atlas, const TexelBakeSettings& settings) {
    if (settings.samples == 0) {
        throw Error("texel bake: 0 samples per texel side");
    }
    const auto start = std::chrono::steady_clock::now();
    const ReferenceRenderer renderer(scene, 0.0, settings.reference);
    const EmbreeScene& geometry = renderer.geometry();
    const PathTracer& tracer = renderer.tracer();
    const std::vector<std::vector<FootprintTriangle>> footprint = footprints(atlas);

    TexelBake out;
    out.radiance = atlas::TexelRadiance::like(atlas.maps);
    std::atomic<std::uint64_t> rays{0}, paths{0}, nonFinite{0}, misses{0};
    const auto texels = static_cast<std::int64_t>(atlas.maps.valid.size());
    auto bake = [&](const tbb::blocked_range<std::int64_t>& range) {
        std::uint64_t localRays = 0, localPaths = 0, localBad = 0, localMisses = 0;
        for (std::int64_t t = range.begin(); t < range.end(); ++t) {
            if (!out.radiance.valid[t] || footprint[t].empty()) continue;
            const glm::vec2 corner(float(t % atlas.maps.width), float((t / atlas.maps.width) % atlas.maps.height));
            glm::dvec3 sum[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
            std::uint32_t finite[2] = {0, 0};
            for (std::uint32_t s = 0; s < settings.samples; ++s) {
                shader::RandomStream rng =
                    shader::blRandomStream(settings.seed ^ kFootprintStream, static_cast<std::uint32_t>(t), s);
                const FootprintTriangle* on = nullptr;
                glm::vec3 b(0.0f);
                for (int draw = 0; draw < kMaxDraws && !on; ++draw) {
                    const glm::vec2 q = corner + shader::blRandom2(rng);
                    for (const FootprintTriangle& f : footprint[t]) {
                        b = barycentric(f.uv, q);
                        if (b.x >= 0.0f && b.y >= 0.0f && b.z >= 0.0f) {
                            on = &f;
                            break;
                        }
                    }
                }
                if (!on) {
                    ++localMisses;
                    continue;
                }
                const glm::vec3 point = b.x * on->position[0] + b.y * on->position[1] + b.z * on->position[2];
                const SurfaceHit at = geometry.surfaceAt(on->mesh, on->triangle, point);
                for (int side = 0; side < 2; ++side) {
                    const PathSample p = tracer.traceLeaving(at, side == 1, static_cast<std::uint32_t>(t), s, settings.seed);
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
        misses += localMisses;
    };
    const int threads = settings.reference.threads > 0 ? settings.reference.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, texels, 64), bake); });
    out.rays = rays;
    out.paths = paths;
    out.nonFiniteSamples = nonFinite;
    out.footprintMisses = misses;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace bl
