#include "modes/atlas/TexelSamples.h"

#include "modes/atlas/AtlasTables.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace bl::atlasmode {

namespace {

struct Pending {
    std::uint32_t texel;
    shader::AtlasSample sample;
};

// One triangle of the link in texel units of its page and in world space at the requested time.
struct TexelTriangle {
    glm::dvec2 uv[3];
    glm::dvec3 p[3];
    std::uint32_t page;
    glm::vec3 normal; // front: counter-clockwise corners
    float density;    // world area per texel-unit area
    int x0, x1, y0, y1; // texels its uv bounding box touches
};

// Barycentrics of p in the uv triangle (a, b, c); true when inside or on an edge.
bool barycentric(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec3& w) {
    const double d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (d == 0.0) return false;
    const double w1 = ((p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y)) / d;
    const double w2 = ((b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y)) / d;
    w = glm::dvec3(1.0 - w1 - w2, w1, w2);
    return w.x >= 0.0 && w.y >= 0.0 && w.z >= 0.0;
}

// Calls `visit` for every triangle with uv and world area.
void forEachTriangle(const Scene& scene, const atlas::TexelMaps& maps, const atlas::AtlasLink& link, double time,
                     const std::function<void(const TexelTriangle&)>& visit) {
    const std::size_t triangleCount = link.indices.size() / 3;
    std::size_t mesh = 0, modelMesh = SIZE_MAX;
    glm::mat4 model(1.0f);
    for (std::size_t tri = 0; tri < triangleCount; ++tri) {
        while (mesh + 1 < link.firstTriangle.size() && tri >= link.firstTriangle[mesh + 1]) ++mesh;
        if (mesh != modelMesh) {
            model = scene.meshes[mesh].animation.at(time);
            modelMesh = mesh;
        }
        TexelTriangle t;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = link.indices[3 * tri + k] + std::uint32_t(link.firstVertex[mesh]);
            t.uv[k] = glm::dvec2(link.atlasVertices[v].uv) * glm::dvec2(maps.width, maps.height);
            t.p[k] = glm::dvec3(model * glm::vec4(glm::vec3(link.vertices[v].positionU), 1.0f));
            t.page = link.atlasVertices[v].page;
        }
        const glm::dvec3 cross = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
        const double worldArea = 0.5 * glm::length(cross);
        const double uvArea = 0.5 * std::abs((t.uv[1].x - t.uv[0].x) * (t.uv[2].y - t.uv[0].y) -
                                             (t.uv[2].x - t.uv[0].x) * (t.uv[1].y - t.uv[0].y));
        if (!(uvArea > 0.0) || !(worldArea > 0.0)) continue;
        t.normal = glm::vec3(cross / (2.0 * worldArea));
        t.density = float(worldArea / uvArea);
        t.x0 = std::max(0, int(std::floor(std::min({t.uv[0].x, t.uv[1].x, t.uv[2].x}))));
        t.x1 = std::min(maps.width - 1, int(std::floor(std::max({t.uv[0].x, t.uv[1].x, t.uv[2].x}))));
        t.y0 = std::max(0, int(std::floor(std::min({t.uv[0].y, t.uv[1].y, t.uv[2].y}))));
        t.y1 = std::min(maps.height - 1, int(std::floor(std::max({t.uv[0].y, t.uv[1].y, t.uv[2].y}))));
        visit(t);
    }
}

} // namespace

TexelSamples buildTexelSamples(const Scene& scene, const atlas::Atlas& atlas, const atlas::AtlasLink& link, int grid,
                               double time) {
    const atlas::TexelMaps& maps = atlas.maps;
    const std::size_t texelCount = std::size_t(maps.width) * maps.height * maps.pages;
    const std::size_t perTexel = std::size_t(grid) * grid;
    auto texelOf = [&](const TexelTriangle& t, int x, int y) {
        return std::uint32_t((std::size_t(t.page) * maps.height + y) * maps.width + x);
    };
    std::vector<Pending> pending;
    // A grid point on an edge shared by two triangles is claimed by the first only.
    std::vector<std::uint8_t> claimed(texelCount * perTexel, 0);
    std::vector<std::uint32_t> count(texelCount, 0);
    forEachTriangle(scene, maps, link, time, [&](const TexelTriangle& t) {
        for (int y = t.y0; y <= t.y1; ++y) {
            for (int x = t.x0; x <= t.x1; ++x) {
                const std::uint32_t texel = texelOf(t, x, y);
                for (std::size_t g = 0; g < perTexel; ++g) {
                    if (claimed[texel * perTexel + g]) continue;
                    const glm::dvec2 q(x + (double(g % grid) + 0.5) / grid, y + (double(g / grid) + 0.5) / grid);
                    glm::dvec3 w;
                    if (!barycentric(q, t.uv[0], t.uv[1], t.uv[2], w)) continue;
                    claimed[texel * perTexel + g] = 1;
                    const glm::dvec3 world = w.x * t.p[0] + w.y * t.p[1] + w.z * t.p[2];
                    pending.push_back({texel, {glm::vec3(world), t.density, t.normal, texel}});
                    ++count[texel];
                }
            }
        }
    });
    // Texels the grid missed (slivers): the point of the first touching triangle nearest the
    // texel centre (its clamped barycentrics).
    forEachTriangle(scene, maps, link, time, [&](const TexelTriangle& t) {
        for (int y = t.y0; y <= t.y1; ++y) {
            for (int x = t.x0; x <= t.x1; ++x) {
                const std::uint32_t texel = texelOf(t, x, y);
                if (count[texel] > 0 || clippedTriangleArea(t.uv[0], t.uv[1], t.uv[2], x, y) <= 0.0) continue;
                glm::dvec3 w;
                barycentric(glm::dvec2(x + 0.5, y + 0.5), t.uv[0], t.uv[1], t.uv[2], w);
                w = glm::max(w, glm::dvec3(0.0));
                w /= (w.x + w.y + w.z);
                const glm::dvec3 world = w.x * t.p[0] + w.y * t.p[1] + w.z * t.p[2];
                pending.push_back({texel, {glm::vec3(world), t.density, t.normal, texel}});
                ++count[texel];
            }
        }
    });
    TexelSamples out;
    out.first.resize(texelCount + 1, 0);
    for (std::size_t t = 0; t < texelCount; ++t) out.first[t + 1] = out.first[t] + count[t];
    out.samples.resize(pending.size());
    std::vector<std::uint32_t> cursor(out.first.begin(), out.first.end() - 1);
    for (const Pending& s : pending) out.samples[cursor[s.texel]++] = s.sample;
    return out;
}

} // namespace bl::atlasmode
