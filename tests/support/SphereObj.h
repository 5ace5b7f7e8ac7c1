// A closed UV sphere as an OBJ file without normals, for tests of what a file without normals is
// shaded with (core/scene/MeshCleanup.h) and of closed-form scenes inside a sphere.
#pragma once

#include <string>

namespace bl::test {

// `rings` x `segments` quads (triangles at the poles) on the unit sphere scaled by `radius`,
// centred at the origin; faces wound counter-clockwise seen from inside when `inward`. No `vn`.
std::string sphereObj(int rings, int segments, float radius, bool inward);

} // namespace bl::test
