// The atlas link on real scenes (the Cornell box, and McGuire's textured teapot): every scene
// triangle maps to an atlas triangle and back, drawn on atlas vertices that carry the scene's
// corners, material uvs and an atlas uv inside the triangle's own chart on its page; and the
// atlas's per-texel albedo equals a direct texture lookup at the texel's surface point.
#include "atlas/AtlasLink.h"
#include "base/Error.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace bl;
using namespace bl::atlas;

namespace {

// The mesh holding scene triangle g.
std::uint32_t meshOf(const AtlasLink& link, std::uint32_t g) {
    return std::uint32_t(std::upper_bound(link.firstTriangle.begin(), link.firstTriangle.end(), g) -
                         link.firstTriangle.begin() - 1);
}

// The page texel under atlas uv `uv` (uv in [0, 1]^2), as an index into the stacked maps.
std::size_t texelUnder(const TexelMaps& maps, glm::vec2 uv, std::uint32_t page) {
    const int x = std::clamp(int(std::floor(uv.x * float(maps.width))), 0, maps.width - 1);
    const int y = std::clamp(int(std::floor(uv.y * float(maps.height))), 0, maps.height - 1);
    return (std::size_t(page) * std::size_t(maps.height) + std::size_t(y)) * std::size_t(maps.width) + std::size_t(x);
}

void expectLinked(const Scene& scene, const Atlas& atlas, const AtlasLink& link) {
    const std::uint32_t triangles = std::uint32_t(scene.triangleCount());
    ASSERT_EQ(link.firstTriangle.size(), scene.meshes.size() + 1);
    ASSERT_EQ(link.firstTriangle.back(), triangles);
    ASSERT_EQ(link.atlasTriangle.size(), triangles);
    ASSERT_EQ(link.sceneTriangle.size(), triangles);
    ASSERT_EQ(link.indices.size(), 3 * std::size_t(triangles));
    ASSERT_EQ(link.atlasVertices.size(), link.vertices.size());
    std::size_t wrongMaps = 0, wrongCorners = 0, outsideChart = 0, wrongPage = 0;
    for (std::uint32_t g = 0; g < triangles; ++g) {
        const std::uint32_t m = meshOf(link, g), f = g - link.firstTriangle[m];
        const std::uint32_t a = link.atlasTriangle[g];
        // There and back, within the same mesh, onto the same triangle.
        if (a >= triangles || link.sceneTriangle[a] != g || meshOf(link, a) != m ||
            atlas.triangleSources[m][a - link.firstTriangle[m]] != f) {
            ++wrongMaps;
            continue;
        }
        const Mesh& sm = scene.meshes[m];
        const std::uint32_t chart = atlas.triangleCharts[m][a - link.firstTriangle[m]];
        const std::uint32_t page = atlas.charts[chart].page;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = std::size_t(link.firstVertex[m]) + link.indices[3 * std::size_t(g) + std::size_t(k)];
            ASSERT_LT(v, link.vertices.size());
            const shader::GpuVertex& gv = link.vertices[v];
            const glm::vec2 materialUv = sm.uvs.empty() ? glm::vec2(0.0f) : sm.uvs[sm.triangles[f][k]];
            wrongCorners += glm::vec3(gv.positionU) != sm.positions[sm.triangles[f][k]] ||
                            glm::vec3(gv.normalV) != sm.normals[sm.triangles[f][k]] || gv.positionU.w != materialUv.x ||
                            gv.normalV.w != materialUv.y;
            const shader::GpuAtlasVertex& av = link.atlasVertices[v];
            wrongPage += av.page != page;
            outsideChart += atlas.maps.chart[texelUnder(atlas.maps, av.uv, page)] != std::int32_t(chart);
        }
    }
    EXPECT_EQ(wrongMaps, 0u);
    EXPECT_EQ(wrongCorners, 0u);
    EXPECT_EQ(wrongPage, 0u);
    EXPECT_EQ(outsideChart, 0u);
    // A covered texel's triangle touches it: its centre lies within half a texel diagonal of the
    // triangle's atlas uvs (the sample point is the triangle's point nearest the centre).
    constexpr float kHalfDiagonal = 0.7072f; // texels, sqrt(2) / 2 rounded up
    const TexelMaps& maps = atlas.maps;
    std::size_t farTexels = 0;
    for (std::size_t t = 0; t < maps.valid.size(); ++t) {
        if (maps.valid[t] != 1) continue;
        const std::uint32_t g = maps.triangle[t], m = meshOf(link, g);
        const glm::vec2 size(float(maps.width), float(maps.height));
        const glm::vec2 centre(float(t % std::size_t(maps.width)) + 0.5f,
                               float((t / std::size_t(maps.width)) % std::size_t(maps.height)) + 0.5f);
        glm::vec2 p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = link.atlasVertices[std::size_t(link.firstVertex[m]) + link.indices[3 * std::size_t(g) + std::size_t(k)]].uv * size;
        }
        // Distance from the centre to the triangle: 0 inside, else to the nearest edge.
        float distance = std::numeric_limits<float>::max();
        int inside = 0;
        for (int k = 0; k < 3; ++k) {
            const glm::vec2 e = p[(k + 1) % 3] - p[k], d = centre - p[k];
            const float s = std::clamp(glm::dot(d, e) / glm::dot(e, e), 0.0f, 1.0f);
            distance = std::min(distance, glm::distance(centre, p[k] + s * e));
            inside += (e.x * d.y - e.y * d.x) >= 0.0f ? 1 : -1;
        }
        farTexels += std::abs(inside) != 3 && distance > kHalfDiagonal;
    }
    EXPECT_EQ(farTexels, 0u);
}

// Barycentrics of p (on the triangle's plane) in triangle (a, b, c), in double.
glm::dvec3 barycentric(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double area = glm::dot(n, n);
    const double u = glm::dot(glm::cross(c - b, p - b), n) / area, v = glm::dot(glm::cross(a - c, p - c), n) / area;
    return {u, v, 1.0 - u - v};
}

// The texture's texel (x, y) (row 0 at the top) decoded, wrapped.
glm::dvec3 texel(const Rgba8Image& img, int x, int y) {
    x = ((x % img.width) + img.width) % img.width;
    y = ((y % img.height) + img.height) % img.height;
    const std::size_t i = 4 * (std::size_t(y) * std::size_t(img.width) + std::size_t(x));
    return {srgbToLinear(img.texels[i] / 255.0f), srgbToLinear(img.texels[i + 1] / 255.0f),
            srgbToLinear(img.texels[i + 2] / 255.0f)};
}

// Written out here rather than through image/BilinearLookup.h: the conventions checked directly.
glm::dvec3 directLookup(const Rgba8Image& img, glm::dvec2 uv) {
    const double fx = (uv.x - std::floor(uv.x)) * img.width - 0.5;
    const double fy = (1.0 - (uv.y - std::floor(uv.y))) * img.height - 0.5; // v = 0 at the bottom
    const int x = int(std::floor(fx)), y = int(std::floor(fy));
    const double tx = fx - std::floor(fx), ty = fy - std::floor(fy);
    return (1 - ty) * ((1 - tx) * texel(img, x, y) + tx * texel(img, x + 1, y)) +
           ty * ((1 - tx) * texel(img, x, y + 1) + tx * texel(img, x + 1, y + 1));
}

// Per covered texel, the albedo against the texture read directly at the texel's surface point;
// returns how many texels were textured.
std::size_t expectAlbedo(const Scene& scene, const Atlas& atlas, const AtlasLink& link, double tolerance) {
    const TexelMaps& maps = atlas.maps;
    std::size_t textured = 0, wrong = 0;
    double worst = 0.0;
    for (std::size_t t = 0; t < maps.valid.size(); ++t) {
        if (maps.valid[t] != 1) continue;
        const std::uint32_t g = maps.triangle[t], m = meshOf(link, g);
        const Mesh& mesh = scene.meshes[m];
        const Material& material = scene.materials[mesh.material];
        if (material.albedoTexture < 0) {
            wrong += maps.albedo[t] != material.albedo;
            continue;
        }
        ++textured;
        const glm::uvec3 tri = mesh.triangles[g - link.firstTriangle[m]];
        const glm::dvec3 b = barycentric(glm::dvec3(maps.position[t]), glm::dvec3(mesh.positions[tri.x]),
                                         glm::dvec3(mesh.positions[tri.y]), glm::dvec3(mesh.positions[tri.z]));
        const glm::dvec2 uv = b.x * glm::dvec2(mesh.uvs[tri.x]) + b.y * glm::dvec2(mesh.uvs[tri.y]) +
                              b.z * glm::dvec2(mesh.uvs[tri.z]);
        const glm::dvec3 expected = directLookup(scene.textures[std::size_t(material.albedoTexture)].image, uv);
        const double error = glm::length(expected - glm::dvec3(maps.albedo[t]));
        worst = std::max(worst, error);
        wrong += !(error <= tolerance);
    }
    EXPECT_EQ(wrong, 0u) << "worst difference " << worst;
    return textured;
}

} // namespace

TEST(AtlasLink, CornellBox) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    const Atlas a = buildAtlas(s, AtlasOptions{256});
    const AtlasLink link = linkAtlas(s, a);
    expectLinked(s, a, link);
    EXPECT_GT(link.vertices.size(), 0u);
    EXPECT_EQ(expectAlbedo(s, a, link, 0.0), 0u); // untextured: exactly the flat albedo
}

TEST(AtlasLink, TexturedTeapotOnPages) {
    BL_SKIP_WITHOUT_SHARED("data/glossy/teapot/teapot.obj");
    Scene s = loadScene(bl::test::sharedPath("data/glossy/teapot/teapot.obj"));
    ASSERT_FALSE(s.textures.empty());
    AtlasOptions o;
    o.texelsPerUnit = 2.0f; // the teapot is about 100 units across: several 256^2 pages
    o.pageSize = 256;
    Atlas a = buildAtlas(s, o);
    ASSERT_GT(a.maps.pages, 1);
    AtlasLink link = linkAtlas(s, a);
    expectLinked(s, a, link);
    // Seams split vertices: more atlas vertices than surface points (distinct positions; the OBJ has
    // no normals, so its faces are shaded flat and each face has vertices of its own already).
    std::size_t surfacePoints = 0;
    for (const Mesh& m : s.meshes) {
        std::uint32_t distinct = 0;
        weldVertices(m, distinct);
        surfacePoints += distinct;
    }
    EXPECT_GT(link.vertices.size(), surfacePoints);
    // The sample point is found in float and its uv recomputed here in double: a few 1e-6 of uv
    // error across texels of up to ~1 in linear colour.
    constexpr double kAlbedoTolerance = 1e-3;
    EXPECT_GT(expectAlbedo(s, a, link, kAlbedoTolerance), 1000u);
}

TEST(AtlasLink, AtlasOfAnotherSceneIsAnError) {
    Scene box = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    Atlas a = buildAtlas(box, AtlasOptions{128});
    Scene other = box;
    other.meshes.pop_back();
    const std::string message = bl::test::errorOf([&] { linkAtlas(other, a); });
    EXPECT_NE(message.find("another scene"), std::string::npos) << message;
    other = box;
    other.meshes[0].triangles.pop_back();
    EXPECT_NE(bl::test::errorOf([&] { linkAtlas(other, a); }).find("mesh 0"), std::string::npos);
}
