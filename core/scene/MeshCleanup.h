// Makes loaded meshes safe for every renderer: drops degenerate and duplicate triangles (counted),
// repairs broken normals, and gives face (flat) or generated (smooth) normals where the file has
// none or the scene asks for them.
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

// Which normals a mesh is shaded with (a [[mesh]]'s `normals` key). A file without normals is shaded
// flat by default, as other renderers shade it: smoothing is a guess about the surface the
// triangles approximate, and a wrong guess changes the image (a closed furnace sphere with
// generated normals reads 1.997 where every radiance is 2).
enum class NormalSource {
    File,   // the file's normals; face normals where it has none (or only some)
    Flat,   // face normals, whatever the file has
    Smooth, // generated: area-weighted, averaged only across edges whose dihedral angle is below
            // creaseDegrees (boxes keep their edges, scans become smooth); the file's are ignored
};

struct NormalOptions {
    NormalSource source = NormalSource::File;
    float creaseDegrees = 45.0f; // Smooth only
};

CleanupStats cleanupMesh(Mesh& mesh, const NormalOptions& normals = {});

} // namespace bl
