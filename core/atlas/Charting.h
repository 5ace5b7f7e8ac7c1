// Charts for the texture atlas: region growing over OpenMesh's half-edge structure. A chart grows
// from its largest unassigned face, cheapest neighbour first, while the face lies within a normal
// cone of the chart's area-weighted normal (which keeps charts developable with little distortion
// and their seams on creases) and its cost, normal deviation plus the seam length it adds, stays
// under a bound (which keeps charts compact with short seams, so they pack tightly). Faces
// OpenMesh cannot add (non-manifold) become charts of their own.
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

struct ChartingOptions {
    float coneDegrees = 45.0f; // largest angle between a face normal and its chart's normal
    float seamWeight = 1.0f;   // weight of the seam-length cost against the normal deviation
};

// A face joins a chart while its cost stays at most this (deviation 1 is the cone's rim).
inline constexpr float kMaxChartingCost = 1.0f;

// Charts of one mesh.
std::vector<ChartFaces> growCharts(const Mesh& mesh, std::uint32_t meshIndex, const ChartingOptions& options,
                                   ChartingStats& stats);

// Index of each vertex among the mesh's distinct positions: OBJ/PLY vertices split by normals or
// texture coordinates are one surface point for charting.
std::vector<std::uint32_t> weldVertices(const Mesh& mesh, std::uint32_t& distinct);

// Splits a set of faces into edge-connected components (sharing an edge of welded vertices).
std::vector<std::vector<std::uint32_t>> connectedComponents(const Mesh& mesh, const std::vector<std::uint32_t>& welded,
                                                            const std::vector<std::uint32_t>& faces);

} // namespace bl::atlas
