// The texture atlas of a scene, the discretization of the `atlas` mode (Hermes et al. 2010,
// papers/EQUATIONS.md [HHGM10 Eq. 3]): charts (core/atlas/Charting.h), flattened (Parameterization.h),
// packed (Packing.h), and per-texel maps of the whole scene.
//
// Coverage: every texel a triangle touches is covered (conservatively, in software: lavapipe has no
// conservative rasterization); its sample point is the texel centre when that lies on a triangle,
// else the nearest point of the nearest touching triangle. Every triangle owns at least one texel
// where possible (texels are taken from triangles that own several). One ring of empty texels
// around each chart is filled from its neighbour (validity 2) so bilinear lookups never read empty
// texels.
#pragma once

#include "atlas/Charting.h"
#include "atlas/Parameterization.h"
#include "scene/Scene.h"

#include <string>
#include <vector>

namespace bl::atlas {

struct AtlasOptions {
    int size = 2048;             // atlas side in texels (when texelsPerUnit is 0)
    float texelsPerUnit = 0.0f;  // fixed density instead: the page grows to fit it, up to pageSize,
    int pageSize = 4096;         // then the charts spill onto further pages of this size
    int padding = 2;             // texels between charts
    ChartingOptions charting;    // normal cone and seam-length weight of the charts
    float maxStretch = 1.5f;     // charts above this L2 stretch are split
    // Charts of their own for sub-texel triangles may take at most singleChartPages times the
    // largest of a page, the rest of the atlas and singleChartFloorTexels; beyond, buildAtlas
    // refuses the scene (Atlas.cpp: refuseOutweighingSingles).
    double singleChartPages = 16.0;
    double singleChartFloorTexels = 512.0 * 512.0;
};

struct AtlasStats {
    double utilization = 0.0; // covered texels / all texels
    std::size_t charts = 0;
    int pages = 1;
    double meanStretch = 0.0; // area-weighted L2 stretch
    double maxStretch = 0.0;  // worst chart
    std::size_t flippedTriangles = 0;
    std::size_t overlappingTexels = 0; // touched by two charts
    std::size_t uncoveredTriangles = 0; // owning no texel
    // Triangles that owned no texel of their chart (slivers or sub-texel triangles crowded by their
    // neighbours) and were given charts of their own: each costs a chart, its padding and often
    // pages beyond the first, and its texels see only its own few hits (noisy, not biased).
    std::size_t isolatedTriangles = 0;
    std::size_t triangles = 0;
    std::size_t nonManifoldFaces = 0;
    std::size_t degenerateFaces = 0;
    double seconds = 0.0;
};

// Per-texel maps of all pages, stacked: texel (x, y) of page p is at index (p * height + y) * width + x.
struct TexelMaps {
    int width = 0;  // of one page
    int height = 0;
    int pages = 1;
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> normal;
    std::vector<std::uint32_t> material;
    std::vector<glm::vec3> emission;
    std::vector<glm::vec3> albedo;    // linear albedo at the sample point (AlbedoLookup: texture or flat)
    std::vector<std::uint32_t> triangle; // scene triangle of the sample point (firstSceneTriangles), 0 if empty
    std::vector<float> area;          // world area the texel stands for
    std::vector<std::uint8_t> valid;  // 0 empty, 1 covered, 2 dilated from a neighbour
    std::vector<std::int32_t> chart;  // owning chart, -1 empty
};

struct Atlas {
    float texelsPerUnit = 0.0f;
    std::vector<FlatChart> charts;     // uv in texel units of the atlas after packing
    std::vector<Mesh> meshes;          // the scene's meshes with atlas uvs in [0,1]^2, vertices split on seams
    std::vector<std::vector<std::uint32_t>> vertexPages; // per mesh, the page of each vertex's uv
    std::vector<std::vector<std::uint32_t>> vertexSources;   // per mesh, the scene vertex each vertex splits
    std::vector<std::vector<std::uint32_t>> triangleSources; // per mesh, the scene triangle (in that mesh) of each triangle
    std::vector<std::vector<std::uint32_t>> triangleCharts;  // per mesh, the chart of each triangle
    TexelMaps maps;
    AtlasStats stats;
};

Atlas buildAtlas(const Scene& scene, const AtlasOptions& options);

// Scene triangle indices number the triangles of the whole scene: meshes in scene order, each
// mesh's triangles in order (GpuScene's numbering: its plane buffer, and first triangle +
// gl_PrimitiveID in a draw). Per mesh, the index of its first triangle, then the total.
std::vector<std::uint32_t> firstSceneTriangles(const Scene& scene);

// The charts in colour (dilated texels darker, empty black), for `bundlelab atlas --out`.
Image chartImage(const TexelMaps& maps);

} // namespace bl::atlas
