#include "support/SphereObj.h"

#include <cmath>
#include <sstream>

namespace bl::test {

std::string sphereObj(int rings, int segments, float radius, bool inward) {
    const double pi = 3.14159265358979323846;
    std::ostringstream obj;
    obj.precision(9);
    // Vertex 1: north pole; then rings - 1 latitude circles of `segments` vertices; last: south pole.
    obj << "v 0 " << radius << " 0\n";
    for (int r = 1; r < rings; ++r) {
        const double theta = pi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double phi = 2.0 * pi * s / segments;
            obj << "v " << radius * std::sin(theta) * std::cos(phi) << " " << radius * std::cos(theta) << " "
                << radius * std::sin(theta) * std::sin(phi) << "\n";
        }
    }
    const int south = 2 + (rings - 1) * segments;
    obj << "v 0 " << -radius << " 0\n";
    auto at = [&](int r, int s) { return 2 + (r - 1) * segments + (s % segments); }; // r in [1, rings - 1]
    // (a, b, c) as listed faces outward (counter-clockwise seen from outside); reversed if inward.
    auto face = [&](int a, int b, int c) {
        if (inward) std::swap(b, c);
        obj << "f " << a << " " << b << " " << c << "\n";
    };
    for (int s = 0; s < segments; ++s) {
        face(1, at(1, s + 1), at(1, s));
        for (int r = 1; r + 1 < rings; ++r) {
            face(at(r, s), at(r, s + 1), at(r + 1, s + 1));
            face(at(r, s), at(r + 1, s + 1), at(r + 1, s));
        }
        face(south, at(rings - 1, s), at(rings - 1, s + 1));
    }
    return obj.str();
}

} // namespace bl::test
