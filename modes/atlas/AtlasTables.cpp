#include "modes/atlas/AtlasTables.h"

#include "atlas/TexelCoverage.h"

#include "base/Error.h"

#include <algorithm>
#include <cmath>

namespace bl::atlasmode {

AtlasTables buildAtlasTables(const atlas::Atlas& atlas, const atlas::AtlasLink& link) {
    const atlas::TexelMaps& maps = atlas.maps;
    const int width = maps.width, height = maps.height;
    const std::size_t texelCount = std::size_t(width) * height * maps.pages;
    AtlasTables t;
    const std::size_t triangleCount = link.indices.size() / 3;
    t.triangles.resize(triangleCount);
    std::vector<double> area(texelCount, 0.0);
    std::size_t mesh = 0;
    for (std::size_t tri = 0; tri < triangleCount; ++tri) {
        while (mesh + 1 < link.firstTriangle.size() && tri >= link.firstTriangle[mesh + 1]) ++mesh;
        std::uint32_t v[3];
        for (int k = 0; k < 3; ++k) v[k] = link.indices[3 * tri + k] + std::uint32_t(link.firstVertex[mesh]);
        shader::AtlasTriangle& out = t.triangles[tri];
        out.uv0 = link.atlasVertices[v[0]].uv;
        out.uv1 = link.atlasVertices[v[1]].uv;
        out.uv2 = link.atlasVertices[v[2]].uv;
        out.page = link.atlasVertices[v[0]].page;
        if (link.atlasVertices[v[1]].page != out.page || link.atlasVertices[v[2]].page != out.page) {
            throw Error("atlas mode: triangle " + std::to_string(tri) + " spans two atlas pages");
        }
        const glm::dvec3 p0 = glm::dvec3(link.vertices[v[0]].positionU);
        const glm::dvec3 p1 = glm::dvec3(link.vertices[v[1]].positionU);
        const glm::dvec3 p2 = glm::dvec3(link.vertices[v[2]].positionU);
        const double worldArea = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        const glm::dvec2 scale(width, height);
        const glm::dvec2 a = glm::dvec2(out.uv0) * scale, b = glm::dvec2(out.uv1) * scale,
                         c = glm::dvec2(out.uv2) * scale;
        const double uvArea = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
        if (!(uvArea > 0.0)) {
            t.degenerateTriangles += worldArea > 0.0;
            continue;
        }
        const double density = worldArea / uvArea; // world area per texel-unit area
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        const int x1 = std::min(width - 1, int(std::floor(std::max({a.x, b.x, c.x}))));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        const int y1 = std::min(height - 1, int(std::floor(std::max({a.y, b.y, c.y}))));
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const double clipped = clippedTriangleArea(a, b, c, x, y);
                if (clipped > 0.0) {
                    area[(std::size_t(out.page) * height + y) * width + x] += clipped * density;
                }
            }
        }
    }
    t.texels.resize(texelCount);
    t.charts = maps.chart;
    for (std::size_t i = 0; i < texelCount; ++i) {
        shader::AtlasTexel& texel = t.texels[i];
        texel.emission = maps.emission[i];
        texel.albedo = maps.albedo[i];
        texel.material = maps.material[i];
        texel.inverseArea = area[i] > 0.0 ? float(1.0 / area[i]) : 0.0f;
        t.totalArea += area[i];
    }
    return t;
}

} // namespace bl::atlasmode
