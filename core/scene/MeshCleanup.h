// Makes loaded meshes safe for every renderer: drops degenerate and duplicate triangles (counted),
// repairs broken normals, and generates normals where the file has none.
#pragma once

#include "scene/Mesh.h"

#include <cstddef>

namespace bl {

struct CleanupStats {
    std::size_t degenerateTriangles = 0; // repeated vertex or (relative) zero area
    std::size_t duplicateTriangles = 0;  // same three positions as an earlier triangle, any order
    std::size_t repairedNormals = 0;     // zero or non-finite normals replaced
    bool generatedNormals = false;
};

// Normals are generated area-weighted, averaged only across edges whose dihedral angle is below
// `creaseDegrees`, so boxes stay flat-shaded and scans stay smooth.
CleanupStats cleanupMesh(Mesh& mesh, float creaseDegrees = 45.0f);

} // namespace bl
