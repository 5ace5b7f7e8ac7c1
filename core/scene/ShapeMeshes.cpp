#include "scene/ShapeMeshes.h"

#include <glm/glm.hpp>

#include <cmath>

namespace bl {

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

Mesh quadMesh(glm::vec3 o, glm::vec3 u, glm::vec3 v) {
    Mesh m;
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    for (const glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
        m.positions.push_back(o + c.x * u + c.y * v);
        m.normals.push_back(n);
        m.uvs.push_back(c);
    }
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

Mesh cubeMesh() {
    Mesh out;
    // Six faces of [-1, 1]^3, each facing out.
    const glm::vec3 faces[6][3] = {{{1, -1, -1}, {0, 2, 0}, {0, 0, 2}},  {{-1, -1, -1}, {0, 0, 2}, {0, 2, 0}},
                                   {{-1, 1, -1}, {0, 0, 2}, {2, 0, 0}},  {{-1, -1, -1}, {2, 0, 0}, {0, 0, 2}},
                                   {{-1, -1, 1}, {2, 0, 0}, {0, 2, 0}},  {{-1, -1, -1}, {0, 2, 0}, {2, 0, 0}}};
    for (const auto& f : faces) {
        const Mesh q = quadMesh(f[0], f[1], f[2]);
        const auto base = static_cast<std::uint32_t>(out.positions.size());
        out.positions.insert(out.positions.end(), q.positions.begin(), q.positions.end());
        out.normals.insert(out.normals.end(), q.normals.begin(), q.normals.end());
        out.uvs.insert(out.uvs.end(), q.uvs.begin(), q.uvs.end());
        for (const glm::uvec3& t : q.triangles) out.triangles.push_back(t + base);
    }
    return out;
}

Mesh diskMesh(int segments) {
    Mesh m;
    m.positions.push_back({0, 0, 0});
    m.normals.push_back({0, 0, 1});
    for (int i = 0; i < segments; ++i) {
        const double a = 2.0 * kPi * i / segments;
        m.positions.push_back({float(std::cos(a)), float(std::sin(a)), 0.0f});
        m.normals.push_back({0, 0, 1});
        m.triangles.push_back({0u, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % segments)});
    }
    return m;
}

Mesh sphereMesh(const glm::dvec3& centre, double radius, int segments) {
    Mesh m;
    const int around = segments, rings = segments / 2;
    for (int r = 0; r <= rings; ++r) {
        const double theta = kPi * r / rings;
        for (int a = 0; a <= around; ++a) {
            const double phi = 2.0 * kPi * a / around;
            const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            m.positions.push_back(glm::vec3(centre + radius * n));
            m.normals.push_back(glm::vec3(n));
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int a = 0; a < around; ++a) {
            const auto i = std::uint32_t(r * (around + 1) + a), j = i + std::uint32_t(around + 1);
            // Outward: counter-clockwise seen from outside.
            if (r > 0) m.triangles.push_back({i, j, i + 1});
            if (r + 1 < rings) m.triangles.push_back({i + 1, j, j + 1});
        }
    }
    return m;
}

} // namespace bl
