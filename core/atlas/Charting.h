// Charts for the texture atlas: region growing over OpenMesh's half-edge structure. A chart grows
// from its largest unassigned face, best-aligned neighbour first, while the face stays within a
// normal cone of the chart's area-weighted normal (which keeps charts developable with little
// distortion and their seams on creases). Faces OpenMesh cannot add (non-manifold) become charts
// of their own.
#pragma once

#include "scene/Mesh.h"

#include <cstdint>
#include <vector>

namespace bl::atlas {

struct ChartFaces {
    std::uint32_t mesh;                 // scene mesh index
    std::vector<std::uint32_t> faces;   // triangle indices in that mesh
};

struct ChartingStats {
    std::size_t nonManifoldFaces = 0;
    std::size_t degenerateFaces = 0; // collapsed when coincident vertices are welded
};

// Charts of one mesh. `coneDegrees`: largest angle between a face normal and its chart's normal.
std::vector<ChartFaces> growCharts(const Mesh& mesh, std::uint32_t meshIndex, float coneDegrees, ChartingStats& stats);

// Index of each vertex among the mesh's distinct positions: OBJ/PLY vertices split by normals or
// texture coordinates are one surface point for charting.
std::vector<std::uint32_t> weldVertices(const Mesh& mesh, std::uint32_t& distinct);

// Splits a set of faces into edge-connected components (sharing an edge of welded vertices).
std::vector<std::vector<std::uint32_t>> connectedComponents(const Mesh& mesh, const std::vector<std::uint32_t>& welded,
                                                            const std::vector<std::uint32_t>& faces);

} // namespace bl::atlas
