// Triangle meshes of simple shapes, for scene formats that describe them analytically (Mitsuba's
// rectangle, cube, disk and sphere): positions, outward (or u x v) normals, uvs where the shape
// has an obvious parameterization. Counter-clockwise seen from the side the normals face.
#pragma once

#include "scene/Mesh.h"

#include <glm/vec3.hpp>

namespace bl {

// One quad: corner `o`, edges `u` and `v`, facing u x v; uv (0, 0) at o, (1, 1) at o + u + v.
Mesh quadMesh(glm::vec3 o, glm::vec3 u, glm::vec3 v);
// [-1, 1]^3, faces outward.
Mesh cubeMesh();
// The unit disk in z = 0 facing +z, `segments` triangles.
Mesh diskMesh(int segments);
// A sphere of `segments` around by segments / 2 from pole to pole, smooth normals outward.
Mesh sphereMesh(const glm::dvec3& centre, double radius, int segments);

} // namespace bl
