// The link between a texture atlas and the GPU scene (issue 10): what GpuScene needs to draw the
// scene on the atlas's vertices, and the triangle map between the two numberings.
//
// Atlas charts split vertices at their seams, so one scene vertex can have several atlas uvs and
// the atlas uv cannot be a per-vertex attribute of the scene's own vertices. The link therefore
// draws the scene's triangles, in the scene's own order (firstSceneTriangles: GpuScene's order, so
// gl_PrimitiveID, the plane buffer and the G-buffer's triangle ids mean the same as without the
// atlas), on the atlas's vertices: each carries the material vertex it was split from (position,
// normal, material uv: binding 0, GpuVertex, so every existing pass draws it unchanged) and its
// atlas uv and page (binding 1, GpuAtlasVertex). Corner order and so winding are the scene's.
//
// Triangle map: the atlas numbers its triangles as the scene does (meshes in order, each atlas mesh
// holding exactly its scene mesh's triangles), but orders them by chart within a mesh; the map is
// a permutation within each mesh, in both directions.
#pragma once

#include "atlas/Atlas.h"

#include <shared/GpuTypes.h>
#include <vector>

namespace bl::atlas {

struct AtlasLink {
    std::vector<std::uint32_t> firstTriangle;  // per mesh, its first scene (= atlas) triangle, then the total
    std::vector<std::uint32_t> atlasTriangle;  // per scene triangle: its atlas triangle (global)
    std::vector<std::uint32_t> sceneTriangle;  // per atlas triangle (global): its scene triangle
    std::vector<std::int32_t> firstVertex;     // per mesh, its first vertex in `vertices` (a draw's vertexOffset)
    std::vector<shader::GpuVertex> vertices;   // the atlas's vertices: position, normal, material uv
    std::vector<shader::GpuAtlasVertex> atlasVertices; // the same vertices' atlas uv and page
    std::vector<std::uint32_t> indices;        // per scene triangle, 3 corners, relative to the mesh's firstVertex
};

// Throws bl::Error when `atlas` was not built from `scene` (mesh or triangle counts differ, or a
// triangle is missing or repeated).
AtlasLink linkAtlas(const Scene& scene, const Atlas& atlas);

} // namespace bl::atlas
